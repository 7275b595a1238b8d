//! Which option sets cover a program's configuration space, for `build` (our own pack) and
//! `validate` (any pack).
//!
//! Which options matter is discovered, not declared: a program is preprocessed with the default
//! values, the options the preprocessor consulted become relevant, and sets are drawn from the
//! relevant options' values; options found only under some of those sets join and the search
//! repeats until it is closed ([`covering_sets`]). Which sets:
//! - all combinations of the relevant options, when there are at most
//!   [`MAX_EXHAUSTIVE_SETS`];
//! - otherwise, every combination of the options the program tests in conditionals
//!   ([`Coverage::Exhaustive`], or [`Coverage::Pairwise`] while that product is at most
//!   [`MAX_PAIRWISE_PRODUCT`]), with options that are only substituted as values varied one
//!   at a time;
//! - under [`Coverage::Pairwise`] with more tested combinations: a covering array in which
//!   every pair of values of any two tested options appears together in some set, plus every
//!   profile.
//!
//! Options at their default are left out of a set, so a set means the same whichever options
//! are relevant, and the empty set is the defaults.

use std::collections::{BTreeMap, BTreeSet};

use crate::option_lines::{OptionKind, OptionSet, OptionValue};

/// Largest product of all relevant options validated in full.
pub const MAX_EXHAUSTIVE_SETS: usize = 4096;
/// Largest product of the tested options that [`Coverage::Pairwise`] still validates in full.
pub const MAX_PAIRWISE_PRODUCT: usize = 256;

/// How many option combinations to validate when they are too many for all of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Coverage {
    /// Every combination of the options each program tests.
    Exhaustive,
    /// Every pair of values of any two tested options, and every profile.
    #[default]
    Pairwise,
}

/// What the validated sets of a program cover, weakest last.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SetsCovered {
    /// Every combination of every option the program reads.
    AllCombinations,
    /// Every combination of the options it tests; substituted values one at a time.
    TestedCombinations,
    /// Every pair of tested option values, and the profiles.
    Pairs,
}

impl SetsCovered {
    pub fn describe(self) -> &'static str {
        match self {
            SetsCovered::AllCombinations => "every combination of the options each program reads",
            SetsCovered::TestedCombinations => {
                "every combination of the options each program tests, substituted values one at a time"
            }
            SetsCovered::Pairs => "every pair of values of the options each program tests, and every profile",
        }
    }
}

/// The options one preprocessing of a program consulted: every macro that decided a
/// conditional or was expanded into the text, and those of them that decided a conditional.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Consulted {
    pub read: BTreeSet<String>,
    pub tested: BTreeSet<String>,
}

/// A program's covering sets, what they cover, and the options its text depends on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CoveringSets {
    pub sets: Vec<OptionSet>,
    pub covered: SetsCovered,
    pub read: BTreeSet<String>,
}

/// The covering sets of one program (see the module docs). `consult` preprocesses the program
/// under each of a batch of sets (in parallel if it likes) and says which macros each
/// consulted; names that are not options in `kinds` are ignored. Every set returned has been
/// through `consult`. Its first error stops the search.
pub fn covering_sets<E>(
    kinds: &BTreeMap<String, OptionKind>,
    coverage: Coverage,
    profiles: &[OptionSet],
    mut consult: impl FnMut(&[&OptionSet]) -> Result<Vec<Consulted>, E>,
) -> Result<CoveringSets, E> {
    let mut relevant: BTreeSet<String> = BTreeSet::new();
    let mut tested: BTreeSet<String> = BTreeSet::new();
    let mut explored: BTreeSet<OptionSet> = BTreeSet::new();
    loop {
        let (sets, covered) = enumerate(&relevant, &tested, kinds, coverage, profiles);
        let fresh: Vec<&OptionSet> = sets.iter().filter(|s| !explored.contains(*s)).collect();
        let mut grew = false;
        for names in consult(&fresh)? {
            for name in names.read.into_iter().filter(|n| kinds.contains_key(n)) {
                grew |= relevant.insert(name);
            }
            for name in names.tested.into_iter().filter(|n| kinds.contains_key(n)) {
                grew |= tested.insert(name);
            }
        }
        explored.extend(fresh.into_iter().cloned());
        if !grew {
            return Ok(CoveringSets { sets, covered, read: relevant });
        }
    }
}

/// The option sets for the relevant options.
fn enumerate(
    relevant: &BTreeSet<String>,
    tested: &BTreeSet<String>,
    kinds: &BTreeMap<String, OptionKind>,
    coverage: Coverage,
    profiles: &[OptionSet],
) -> (Vec<OptionSet>, SetsCovered) {
    let choices = |name: &String| -> Vec<Option<OptionValue>> {
        let kind = &kinds[name];
        let default = kind.default_value();
        kind.all_values().into_iter().map(|v| (v != default).then_some(v)).collect()
    };
    let set_of = |names: &[&String], row: &[usize]| -> OptionSet {
        names
            .iter()
            .zip(row)
            .filter_map(|(name, &i)| Some(((*name).clone(), choices(name)[i].clone()?)))
            .collect()
    };
    let all: Vec<&String> = relevant.iter().collect();
    let sizes = |names: &[&String]| names.iter().map(|n| choices(n).len()).collect::<Vec<_>>();
    let product_of_all = sizes(&all).iter().try_fold(1usize, |acc, &n| acc.checked_mul(n));
    if product_of_all.is_some_and(|n| n <= MAX_EXHAUSTIVE_SETS) {
        let sets = product(&sizes(&all)).iter().map(|row| set_of(&all, row)).collect();
        return (sets, SetsCovered::AllCombinations);
    }
    let structural: Vec<&String> = relevant.iter().filter(|n| tested.contains(*n)).collect();
    let structural_sizes = sizes(&structural);
    let tested_product = structural_sizes.iter().try_fold(1usize, |acc, &n| acc.checked_mul(n));
    let all_tested = coverage == Coverage::Exhaustive || tested_product.is_some_and(|n| n <= MAX_PAIRWISE_PRODUCT);
    let (rows, covered) = if all_tested {
        (product(&structural_sizes), SetsCovered::TestedCombinations)
    } else {
        (pairwise(&structural_sizes), SetsCovered::Pairs)
    };
    let mut sets: Vec<OptionSet> = rows.iter().map(|row| set_of(&structural, row)).collect();
    for name in relevant.iter().filter(|n| !tested.contains(*n)) {
        for value in choices(name).into_iter().flatten() {
            sets.push([(name.clone(), value)].into());
        }
    }
    if covered == SetsCovered::Pairs {
        for profile in profiles {
            let set: OptionSet = profile
                .iter()
                .filter(|(name, value)| relevant.contains(*name) && kinds[*name].default_value() != **value)
                .map(|(k, v)| (k.clone(), v.clone()))
                .collect();
            sets.push(set);
        }
    }
    sets.sort();
    sets.dedup();
    (sets, covered)
}

/// Every combination of indices below `sizes`.
fn product(sizes: &[usize]) -> Vec<Vec<usize>> {
    let mut rows = vec![Vec::new()];
    for &size in sizes {
        rows = rows.into_iter().flat_map(|row| (0..size).map(move |v| [row.clone(), vec![v]].concat())).collect();
    }
    rows
}

/// A covering array of strength 2: rows of indices below `sizes` such that every pair of
/// values of any two positions appears in some row. Greedy and deterministic: each row starts
/// from an uncovered pair and fills the other positions with the value covering most pairs.
fn pairwise(sizes: &[usize]) -> Vec<Vec<usize>> {
    let n = sizes.len();
    let mut uncovered: BTreeSet<(usize, usize, usize, usize)> = BTreeSet::new();
    for a in 0..n {
        for b in a + 1..n {
            for va in 0..sizes[a] {
                for vb in 0..sizes[b] {
                    uncovered.insert((a, va, b, vb));
                }
            }
        }
    }
    // The all-defaults row first: index 0 is each option's default.
    let mut rows = vec![vec![0; n]];
    remove_covered(&mut uncovered, &rows[0]);
    while let Some(&(a, va, b, vb)) = uncovered.iter().next() {
        let mut row: Vec<Option<usize>> = vec![None; n];
        row[a] = Some(va);
        row[b] = Some(vb);
        for position in 0..n {
            if row[position].is_some() {
                continue;
            }
            let gain = |value: usize| {
                row.iter()
                    .enumerate()
                    .filter_map(|(other, v)| Some((other, (*v)?)))
                    .filter(|&(other, v)| {
                        let key = if other < position { (other, v, position, value) } else { (position, value, other, v) };
                        uncovered.contains(&key)
                    })
                    .count()
            };
            let best = (0..sizes[position]).max_by_key(|&v| (gain(v), std::cmp::Reverse(v))).unwrap_or(0);
            row[position] = Some(best);
        }
        let row: Vec<usize> = row.into_iter().map(|v| v.unwrap_or(0)).collect();
        remove_covered(&mut uncovered, &row);
        rows.push(row);
    }
    rows
}

fn remove_covered(uncovered: &mut BTreeSet<(usize, usize, usize, usize)>, row: &[usize]) {
    for a in 0..row.len() {
        for b in a + 1..row.len() {
            uncovered.remove(&(a, row[a], b, row[b]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairwise_covers_every_pair_with_few_rows() {
        let sizes = [2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 3, 2];
        let rows = pairwise(&sizes);
        for a in 0..sizes.len() {
            for b in a + 1..sizes.len() {
                for va in 0..sizes[a] {
                    for vb in 0..sizes[b] {
                        assert!(rows.iter().any(|r| r[a] == va && r[b] == vb), "pair ({a}={va}, {b}={vb}) uncovered");
                    }
                }
            }
        }
        assert_eq!(rows[0], vec![0; sizes.len()]);
        assert!(rows.len() <= 16, "{} rows", rows.len());
    }

    #[test]
    fn product_lists_every_combination() {
        assert_eq!(product(&[2, 3]).len(), 6);
        assert_eq!(product(&[]), vec![Vec::<usize>::new()]);
    }

    fn switch(default: bool) -> OptionKind {
        OptionKind::Switch { default }
    }

    /// A program that tests A, and B only where A is on: B is found under A=on.
    #[test]
    fn the_search_finds_options_behind_other_options() {
        let kinds: BTreeMap<String, OptionKind> = [("A".to_string(), switch(false)), ("B".to_string(), switch(false))].into();
        let mut seen = Vec::new();
        let found = covering_sets::<()>(&kinds, Coverage::Pairwise, &[], |sets| {
            seen.extend(sets.iter().map(|s| (*s).clone()));
            Ok(sets
                .iter()
                .map(|set| {
                    let mut names: BTreeSet<String> = ["A".to_string(), "NOT_AN_OPTION".to_string()].into();
                    if set.get("A") == Some(&OptionValue::Switch(true)) {
                        names.insert("B".into());
                    }
                    Consulted { read: names.clone(), tested: names }
                })
                .collect())
        })
        .unwrap();
        assert_eq!(found.covered, SetsCovered::AllCombinations);
        assert_eq!(found.read, ["A".to_string(), "B".to_string()].into());
        assert_eq!(found.sets.len(), 4);
        assert!(found.sets.iter().all(|s| seen.contains(s)), "every set returned was consulted");
        assert_eq!(seen.len(), 4, "no set is consulted twice: {seen:?}");
    }

    /// Past the exhaustive limit, values only substituted into the text vary one at a time.
    #[test]
    fn substituted_values_vary_one_at_a_time() {
        let values: Vec<String> = (0..20).map(|v| v.to_string()).collect();
        let value = || OptionKind::Value { default: "0".into(), values: values.clone() };
        let kinds: BTreeMap<String, OptionKind> =
            [("X".to_string(), value()), ("Y".to_string(), value()), ("Z".to_string(), value())].into();
        let found = covering_sets::<()>(&kinds, Coverage::Pairwise, &[], |sets| {
            let names: BTreeSet<String> = ["X", "Y", "Z"].map(String::from).into();
            Ok(sets.iter().map(|_| Consulted { read: names.clone(), tested: BTreeSet::new() }).collect())
        })
        .unwrap();
        assert_eq!(found.covered, SetsCovered::TestedCombinations);
        assert_eq!(found.sets.len(), 1 + 3 * 19);
    }
}
