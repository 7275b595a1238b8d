//! Which option sets cover a program's configuration space, for `build` (our own pack) and
//! `validate` (any pack).
//!
//! Which options matter is discovered, not declared: a program is preprocessed with the default
//! values, the options the preprocessor consulted become relevant, and sets are drawn from the
//! relevant options' values; options found only under some of those sets join and the search
//! repeats until it is closed ([`covering_sets`]). Which sets:
//! - under [`Coverage::Exhaustive`], all combinations of the relevant options' values, when
//!   there are at most [`MAX_EXHAUSTIVE_SETS`];
//! - otherwise, every combination of the options the program tests in conditionals
//!   ([`Coverage::Exhaustive`], or [`Coverage::Pairwise`] while that product is at most
//!   [`MAX_PAIRWISE_PRODUCT`]), with options that are only substituted as values tried once
//!   each (see below);
//! - under [`Coverage::Pairwise`] with more tested combinations: a covering array in which
//!   every pair of values of any two tested options appears together in some set, plus every
//!   profile.
//!
//! Outside that first case, a value option's values can be narrowed to [`representatives`]:
//! those on either side of each number its conditionals compare it with, where the rest of
//! its values only change numbers substituted into the text. Values that do not pair (of
//! options only substituted, and tested options' other values) are tried once per kind of
//! literal (int, float, zero, negative, each word), many options in one set: substituted
//! values that differ only by a number of the same form validate alike.
//!
//! Options at their default are left out of a set, so a set means the same whichever options
//! are relevant, and the empty set is the defaults.

use std::collections::{BTreeMap, BTreeSet};

use crate::option_lines::{OptionKind, OptionSet, OptionValue};

/// Largest product of all relevant options validated in full.
pub const MAX_EXHAUSTIVE_SETS: usize = 4096;
/// Largest product of the tested options that [`Coverage::Pairwise`] still validates in full.
pub const MAX_PAIRWISE_PRODUCT: usize = 16;

/// How many option combinations to validate when they are too many for all of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Coverage {
    /// Every combination of the values of the options each program reads where they are at most
    /// [`MAX_EXHAUSTIVE_SETS`], else every combination of the options it tests.
    Exhaustive,
    /// Every combination of the options each program tests while they are few, else every pair of
    /// values of any two of them and every profile; substituted values one per kind of literal.
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
                "every combination of the options each program tests, substituted values one per kind of literal"
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
    representatives: &Representatives,
    coverage: Coverage,
    profiles: &[OptionSet],
    mut consult: impl FnMut(&[&OptionSet]) -> Result<Vec<Consulted>, E>,
) -> Result<CoveringSets, E> {
    let mut relevant: BTreeSet<String> = BTreeSet::new();
    let mut tested: BTreeSet<String> = BTreeSet::new();
    let mut explored: BTreeSet<OptionSet> = BTreeSet::new();
    loop {
        let (sets, covered) = enumerate(&relevant, &tested, kinds, representatives, coverage, profiles);
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

/// Per value option, the values its conditionals can tell apart (see [`representatives`]);
/// an option not listed pairs with all its values.
pub type Representatives = BTreeMap<String, Vec<OptionValue>>;

/// The representatives of each numeric value option in `sources`: its default, its smallest
/// and largest values, and for each number on a `#if`, `#elif` or `#define` line that names
/// the option, that number and the nearest values below and above it. Every interval between
/// those numbers then has a value, so a comparison of the option with any of them (`X == 0`,
/// `X > 2`) takes each outcome it can in some set. An option on a line whose numbers are not
/// all literals it could be compared with (another value option on the same line, a
/// non-numeric value) keeps all its values.
pub fn representatives<'t>(kinds: &BTreeMap<String, OptionKind>, sources: impl IntoIterator<Item = &'t str>) -> Representatives {
    let numeric: BTreeMap<&str, Vec<(f64, &String)>> = kinds
        .iter()
        .filter_map(|(name, kind)| match kind {
            OptionKind::Value { values, .. } => {
                let parsed: Option<Vec<(f64, &String)>> = values.iter().map(|v| number(v).map(|n| (n, v))).collect();
                Some((name.as_str(), parsed?))
            }
            OptionKind::Switch { .. } => None,
        })
        .collect();
    let mut literals: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    let mut unnarrowed: BTreeSet<&str> = BTreeSet::new();
    for text in sources {
        for line in text.lines() {
            let line = line.trim_start();
            let Some(directive) = line.strip_prefix('#') else { continue };
            let directive = directive.trim_start();
            if !["if", "elif", "define"].iter().any(|d| directive.starts_with(d)) {
                continue;
            }
            let code = directive.split("//").next().unwrap_or_default();
            let words: Vec<&str> = code.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.')).filter(|w| !w.is_empty()).collect();
            let named: Vec<&str> = words.iter().copied().filter(|w| numeric.contains_key(w)).collect();
            if named.is_empty() {
                continue;
            }
            // `#define X 4 // [2 4 8]` declares X: its own numbers are its values.
            let declares = directive.starts_with("define") && words.get(1).is_some_and(|w| named.first() == Some(w)) && named.len() == 1;
            if declares {
                continue;
            }
            let numbers: Vec<f64> = words.iter().filter_map(|w| number(w)).collect();
            for name in &named {
                if named.len() > 1 {
                    unnarrowed.insert(name);
                }
                literals.entry(name).or_default().extend(&numbers);
            }
        }
    }
    let mut found = Representatives::new();
    for (name, values) in &numeric {
        if unnarrowed.contains(name) {
            continue;
        }
        let Some(OptionKind::Value { default, .. }) = kinds.get(*name) else { continue };
        let mut sorted = values.clone();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut chosen: BTreeSet<&String> = [default].into();
        chosen.extend(sorted.first().map(|v| v.1));
        chosen.extend(sorted.last().map(|v| v.1));
        for &c in literals.get(name).into_iter().flatten() {
            chosen.extend(sorted.iter().rev().find(|v| v.0 < c).map(|v| v.1));
            chosen.extend(sorted.iter().find(|v| v.0 == c).map(|v| v.1));
            chosen.extend(sorted.iter().find(|v| v.0 > c).map(|v| v.1));
        }
        if chosen.len() < values.len() {
            found.insert(name.to_string(), chosen.into_iter().map(|v| OptionValue::Value(v.clone())).collect());
        }
    }
    found
}

/// The kind of literal an option value is, as substituted into GLSL: an int, a float, negative
/// or zero (which array sizes and divisions tell apart), or a word, which stands only for
/// itself.
fn literal_form(value: &OptionValue) -> String {
    let OptionValue::Value(text) = value else { return value.to_string() };
    let Some(n) = number(text) else { return format!("word {text}") };
    let float = text.contains(['.', 'e', 'E']) || text.ends_with(['f', 'F']);
    let sign = if n == 0.0 { "zero" } else if n < 0.0 { "negative" } else { "positive" };
    format!("{} {sign}", if float { "float" } else { "int" })
}

/// A GLSL number as written in an option value or a condition (`2`, `0.5`, `-1`, `1.0f`).
fn number(text: &str) -> Option<f64> {
    let trimmed = text.trim_end_matches(['f', 'F', 'u', 'U']);
    trimmed.parse::<f64>().ok().filter(|n| n.is_finite())
}

/// The option sets for the relevant options.
fn enumerate(
    relevant: &BTreeSet<String>,
    tested: &BTreeSet<String>,
    kinds: &BTreeMap<String, OptionKind>,
    representatives: &Representatives,
    coverage: Coverage,
    profiles: &[OptionSet],
) -> (Vec<OptionSet>, SetsCovered) {
    let choices = |name: &String| -> Vec<Option<OptionValue>> {
        let kind = &kinds[name];
        let default = kind.default_value();
        kind.all_values().into_iter().map(|v| (v != default).then_some(v)).collect()
    };
    // Every value of every option, where that is few enough and asked for.
    let all: Vec<&String> = relevant.iter().collect();
    let sizes: Vec<usize> = all.iter().map(|name| choices(name).len()).collect();
    if coverage == Coverage::Exhaustive && sizes.iter().try_fold(1usize, |acc, &n| acc.checked_mul(n)).is_some_and(|n| n <= MAX_EXHAUSTIVE_SETS) {
        let sets = product(&sizes)
            .iter()
            .map(|row| all.iter().zip(row).filter_map(|(name, &i)| Some(((*name).clone(), choices(name)[i].clone()?))).collect())
            .collect();
        return (sets, SetsCovered::AllCombinations);
    }
    // Tested options combine through their representatives; their other values, like those of
    // options only substituted, stand one per kind of literal for the rest.
    let narrowed = |name: &String| -> Vec<Option<OptionValue>> {
        match representatives.get(name) {
            Some(values) => choices(name).into_iter().filter(|v| v.as_ref().is_none_or(|v| values.contains(v))).collect(),
            None => choices(name),
        }
    };
    let paired = |name: &String| if tested.contains(name) { narrowed(name) } else { vec![None] };
    let unpaired_values = |name: &String| -> Vec<OptionValue> {
        let paired = paired(name);
        let mut forms: BTreeSet<String> = BTreeSet::new();
        choices(name).into_iter().filter(|v| !paired.contains(v)).flatten().filter(|v| forms.insert(literal_form(v))).collect()
    };
    let structural: Vec<&String> = relevant.iter().filter(|n| tested.contains(*n)).collect();
    let structural_sizes: Vec<usize> = structural.iter().map(|n| narrowed(n).len()).collect();
    let tested_product = structural_sizes.iter().try_fold(1usize, |acc, &n| acc.checked_mul(n));
    let all_tested = coverage == Coverage::Exhaustive || tested_product.is_some_and(|n| n <= MAX_PAIRWISE_PRODUCT);
    let (rows, covered) = if all_tested {
        (product(&structural_sizes), SetsCovered::TestedCombinations)
    } else {
        (pairwise(&structural_sizes), SetsCovered::Pairs)
    };
    let mut sets: Vec<OptionSet> = rows
        .iter()
        .map(|row| structural.iter().zip(row).filter_map(|(name, &i)| Some(((*name).clone(), narrowed(name)[i].clone()?))).collect())
        .collect();
    // Values that do not pair, as few sets as the option with the most of them needs: the
    // k-th set gives every such option its k-th value.
    let singles: Vec<(&String, Vec<OptionValue>)> =
        relevant.iter().map(|name| (name, unpaired_values(name))).filter(|(_, values)| !values.is_empty()).collect();
    let rows_of_singles = singles.iter().map(|(_, values)| values.len()).max().unwrap_or(0);
    for k in 0..rows_of_singles {
        sets.push(singles.iter().filter_map(|(name, values)| Some(((*name).clone(), values.get(k)?.clone()))).collect());
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
        let found = covering_sets::<()>(&kinds, &Representatives::new(), Coverage::Pairwise, &[], |sets| {
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
        assert_eq!(found.covered, SetsCovered::TestedCombinations);
        assert_eq!(found.read, ["A".to_string(), "B".to_string()].into());
        assert_eq!(found.sets.len(), 4);
        assert!(found.sets.iter().all(|s| seen.contains(s)), "every set returned was consulted");
        assert_eq!(seen.len(), 4, "no set is consulted twice: {seen:?}");
    }

    /// Values only substituted into the text are tried once per kind
    /// of literal, several options in one set.
    #[test]
    fn substituted_values_are_tried_once_per_kind_of_literal() {
        let values: Vec<String> = (0..20).map(|v| v.to_string()).collect();
        let value = || OptionKind::Value { default: "0".into(), values: values.clone() };
        let kinds: BTreeMap<String, OptionKind> =
            [("X".to_string(), value()), ("Y".to_string(), value()), ("Z".to_string(), value())].into();
        let found = covering_sets::<()>(&kinds, &Representatives::new(), Coverage::Pairwise, &[], |sets| {
            let names: BTreeSet<String> = ["X", "Y", "Z"].map(String::from).into();
            Ok(sets.iter().map(|_| Consulted { read: names.clone(), tested: BTreeSet::new() }).collect())
        })
        .unwrap();
        assert_eq!(found.covered, SetsCovered::TestedCombinations);
        // The defaults, then one set with each option at 1: every other value is a positive int.
        assert_eq!(found.sets.len(), 2, "{:?}", found.sets);
        let mixed = OptionKind::Value { default: "1.0".into(), values: ["0.5", "1.0", "2", "0", "-1", "-2", "4"].map(String::from).to_vec() };
        let forms: BTreeSet<String> = mixed.all_values().iter().filter(|v| v.to_string() != "1.0").map(literal_form).collect();
        assert_eq!(forms.len(), 4, "float, positive int, zero, negative: {forms:?}");
    }

    /// `DOF_DEPTH == 0` and `LUT > 0` tell apart two kinds of value each: those pair, the
    /// others are each tried once.
    #[test]
    fn compared_values_pair_through_representatives() {
        let listed = |default: &str, values: &[&str]| OptionKind::Value {
            default: default.into(),
            values: values.iter().map(|v| v.to_string()).collect(),
        };
        let depths: Vec<String> = (0..30).map(|v| (2 * v).to_string()).collect();
        let luts: Vec<String> = (0..21).map(|v| v.to_string()).collect();
        let kinds: BTreeMap<String, OptionKind> = [
            ("DOF_DEPTH".to_string(), listed("0", &depths.iter().map(String::as_str).collect::<Vec<_>>())),
            ("LUT".to_string(), listed("0", &luts.iter().map(String::as_str).collect::<Vec<_>>())),
            ("BOTH".to_string(), listed("1", &["1", "2", "3", "4"])),
            ("WORDS".to_string(), listed("low", &["low", "mid", "high"])),
        ]
        .into();
        let source = "#define DOF_DEPTH 0 // [0 2 4]\n#if DOF_DEPTH == 0\n#endif\n  #if LUT > 0 // 7 in a comment\n#endif\n#if BOTH > LUT\n#endif\n";
        let found = representatives(&kinds, [source]);
        let values = |name: &str| found[name].iter().map(|v| v.to_string()).collect::<Vec<_>>();
        assert_eq!(values("DOF_DEPTH"), ["0", "2", "58"]);
        assert!(!found.contains_key("LUT"), "compared with another option: every value");
        assert!(!found.contains_key("BOTH"));
        assert!(!found.contains_key("WORDS"), "not numbers");
        let alone = representatives(&kinds, ["#if DOF_DEPTH == 0\n#endif\n#if LUT > 0\n#endif\n"]);
        assert_eq!(alone["LUT"].iter().map(|v| v.to_string()).collect::<Vec<_>>(), ["0", "1", "20"]);
        // Both tested, and a substituted STEPS too many for every combination.
        let mut kinds = kinds;
        kinds.insert("STEPS".into(), listed("1", &["1", "2", "3", "4", "5", "6", "7", "8", "9", "10"]));
        let found = covering_sets::<()>(&kinds, &alone, Coverage::Pairwise, &[], |sets| {
            let tested: BTreeSet<String> = ["DOF_DEPTH", "LUT"].map(String::from).into();
            let read: BTreeSet<String> = ["DOF_DEPTH", "LUT", "STEPS"].map(String::from).into();
            Ok(sets.iter().map(|_| Consulted { read: read.clone(), tested: tested.clone() }).collect())
        })
        .unwrap();
        assert_eq!(found.covered, SetsCovered::TestedCombinations);
        // 3 × 3 pairs; the other values of all three are positive ints: one more set.
        assert_eq!(found.sets.len(), 3 * 3 + 1, "{:?}", found.sets);
    }
}
