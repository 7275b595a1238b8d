//! Which (program, option set) pairs to validate: every program under each set asked for, or,
//! with [`crate::Profiles::Covering`], each program under the covering sets of its own options
//! ([`tidepack_loader::coverage`]). Pairs whose program text is identical to one already
//! planned are dropped, so each distinct expanded text is validated once, and `--shard`
//! keeps its share of the rest.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::sync::Mutex;

use rayon::prelude::*;
use sha2::{Digest, Sha256};

use tidepack_glsl::preprocess::{self, PreprocessOptions};
use tidepack_loader::coverage::{self, Consulted, Coverage, Representatives, SetsCovered};
use tidepack_loader::directives::custom_names;
use tidepack_loader::option_lines::{OptionKind, OptionSet};
use tidepack_loader::option_space::{menu_options, read_properties};
use tidepack_loader::programs::Program;
use tidepack_loader::{PackFiles, SetProvider};

/// A digest of what a program is under one option set: its stages' expanded texts (with the
/// file and line each line came from, or the preprocessing error) and the names
/// shaders.properties gives it there.
pub(crate) type Fingerprint = [u8; 32];

/// One program under one option set.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pair {
    pub program: usize,
    pub set: usize,
    pub fingerprint: Option<Fingerprint>,
}

/// Part `index` (0-based) of `count` equal parts of the work, for a CI matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Reads `K/N` (1-based K, as CI matrices count).
    pub fn parse(text: &str) -> Result<Shard, String> {
        let bad = || format!("--shard takes K/N with 1 <= K <= N (such as 2/4), not `{}`", text.escape_debug());
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let (k, n): (usize, usize) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if k == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { index: k - 1, count: n })
    }

    fn keeps(&self, fingerprint: &Fingerprint) -> bool {
        let value = u64::from_le_bytes(fingerprint[..8].try_into().expect("8 bytes"));
        value % self.count as u64 == self.index as u64
    }
}

/// The option sets validated, each once, with its label.
pub(crate) struct SetTable {
    pub sets: Vec<(String, OptionSet)>,
    index: HashMap<OptionSet, usize>,
}

impl SetTable {
    pub fn new(sets: Vec<(String, OptionSet)>) -> SetTable {
        let mut table = SetTable { sets: Vec::new(), index: HashMap::new() };
        for (label, set) in sets {
            table.intern(set, || label);
        }
        table
    }

    /// The index of `set`, added with `label()` if new.
    pub fn intern(&mut self, set: OptionSet, label: impl FnOnce() -> String) -> usize {
        if let Some(&index) = self.index.get(&set) {
            return index;
        }
        self.sets.push((label(), set.clone()));
        self.index.insert(set, self.sets.len() - 1);
        self.sets.len() - 1
    }
}

/// The command-line words that select `set` (`--set BLOOM=off --set SSR_STEPS=24`), or
/// `defaults`.
pub(crate) fn label_of(set: &OptionSet) -> String {
    if set.is_empty() {
        return "defaults".into();
    }
    set.iter().map(|(name, value)| format!("--set {name}={value}")).collect::<Vec<_>>().join(" ")
}

/// What the plan needs to read a pack's programs under a set.
pub(crate) struct Reader<'a> {
    pub pack: &'a PackFiles,
    pub properties_text: &'a str,
    pub declared: &'a BTreeMap<String, OptionKind>,
    pub standard: &'a tidepack_loader::macros::StandardMacros,
    pub macros: &'a PreprocessOptions,
    /// Digest of the custom names per set of the options shaders.properties names, computed
    /// once per such set.
    names: Mutex<HashMap<OptionSet, [u8; 32]>>,
    /// The words of shaders.properties' conditional lines and `program.<name>.enabled`
    /// expressions: the only places where an option's value changes what the file says.
    properties_words: BTreeSet<String>,
}

impl<'a> Reader<'a> {
    pub fn new(
        pack: &'a PackFiles,
        properties_text: &'a str,
        declared: &'a BTreeMap<String, OptionKind>,
        standard: &'a tidepack_loader::macros::StandardMacros,
        macros: &'a PreprocessOptions,
    ) -> Self {
        // A line continued by a trailing `\` reads as much as the line it continues.
        let mut continued = false;
        let reads_options = |line: &&str| {
            let trimmed = line.trim_start();
            let reads = continued || trimmed.starts_with('#') || (trimmed.starts_with("program.") && trimmed.contains(".enabled"));
            continued = reads && line.trim_end().ends_with('\\');
            reads
        };
        let properties_words = properties_text
            .lines()
            .filter(reads_options)
            .flat_map(|line| line.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')))
            .filter(|w| !w.is_empty())
            .map(str::to_string)
            .collect();
        Reader { pack, properties_text, declared, standard, macros, names: Mutex::new(HashMap::new()), properties_words }
    }

    /// `set` as shaders.properties sees it: the values of the options it names.
    pub fn properties_key(&self, set: &OptionSet) -> OptionSet {
        set.iter().filter(|(name, _)| self.properties_words.contains(name.as_str())).map(|(k, v)| (k.clone(), v.clone())).collect()
    }

    fn names_digest(&self, set: &OptionSet) -> [u8; 32] {
        let named = self.properties_key(set);
        if let Some(digest) = self.names.lock().unwrap_or_else(|e| e.into_inner()).get(&named) {
            return *digest;
        }
        let properties = read_properties(self.properties_text, self.standard, self.declared, &named);
        let digest: [u8; 32] = Sha256::digest(format!("{:?}", custom_names(&properties)).as_bytes()).into();
        self.names.lock().unwrap_or_else(|e| e.into_inner()).insert(named, digest);
        digest
    }

    /// Preprocesses every stage of `program` under `set`: the options consulted and the
    /// program's fingerprint there.
    pub fn read(&self, program: &Program, set: &OptionSet) -> (Consulted, Fingerprint) {
        let provider = SetProvider::new(self.pack, set);
        let mut hasher = Sha256::new();
        hasher.update(program.id().as_bytes());
        hasher.update(self.names_digest(set));
        let mut consulted = Consulted::default();
        let paths = program.stages.iter().map(|(_, p)| p).chain(&program.other_stages).chain(&program.compute);
        for path in paths {
            hasher.update(b"\0stage\0");
            hasher.update(path.as_bytes());
            match preprocess::preprocess(&provider, path, self.macros) {
                Ok(pre) => {
                    hasher.update(pre.text.as_bytes());
                    for line in &pre.lines {
                        hasher.update(pre.files[line.file as usize].as_bytes());
                        hasher.update(line.line.to_le_bytes());
                    }
                    consulted.read.extend(pre.consulted_macros);
                    consulted.tested.extend(pre.tested_macros);
                }
                Err(error) => hasher.update(format!("\0error\0{error}").as_bytes()),
            }
        }
        (consulted, hasher.finalize().into())
    }
}

/// How the pairs were chosen, for the summary.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PlanSummary {
    /// The weakest coverage over the programs, with [`crate::Profiles::Covering`].
    pub covered: Option<SetsCovered>,
    /// (program, set) pairs considered.
    pub considered: usize,
    /// Pairs dropped because the program's text was identical under an earlier set.
    pub identical: usize,
    /// Pairs left to other shards.
    pub other_shards: usize,
}

/// The pairs to validate. `global` sets apply to every program in `runnable`; with
/// `covering`, each program also gets the covering sets of the options the menu shows (each with `overrides` over it, the
/// options `overrides` names held fixed). With `dedup` (which `covering` and `shard` need),
/// pairs are fingerprinted and a repeat of a program's text is dropped.
#[allow(clippy::too_many_arguments)]
pub(crate) fn plan(
    reader: &Reader,
    programs: &[Program],
    runnable: &[usize],
    table: &mut SetTable,
    covering: Option<Coverage>,
    overrides: &OptionSet,
    dedup: bool,
    shard: Option<Shard>,
) -> (Vec<Pair>, PlanSummary) {
    let global: Vec<usize> = (0..table.sets.len()).collect();
    let profiles: Vec<OptionSet> = table.sets.iter().map(|(_, set)| set.clone()).collect();
    // What a player can pick: the options the menu shows, but those `--set` holds fixed.
    let defaults = read_properties(reader.properties_text, reader.standard, reader.declared, &OptionSet::new());
    let free: BTreeMap<String, OptionKind> =
        menu_options(&defaults, reader.declared).into_iter().filter(|(name, _)| !overrides.contains_key(name)).collect();
    let representatives = match covering {
        Some(_) => coverage::representatives(&free, reader.pack.texts.values().map(|t| &**t)),
        None => Representatives::new(),
    };
    // Per program: its sets with their fingerprints, in the order they were found.
    type Found = (Vec<(OptionSet, Option<Fingerprint>)>, Option<SetsCovered>);
    let per_program: Vec<Found> = runnable
        .par_iter()
        .map(|&index| {
            let program = &programs[index];
            let mut found: Vec<(OptionSet, Option<Fingerprint>)> = global
                .iter()
                .map(|&s| {
                    let set = &table.sets[s].1;
                    (set.clone(), dedup.then(|| reader.read(program, set).1))
                })
                .collect();
            if let Some(coverage) = covering {
                let mut fingerprints: HashMap<OptionSet, Fingerprint> = HashMap::new();
                let result = coverage::covering_sets::<std::convert::Infallible>(&free, &representatives, coverage, &profiles, |sets| {
                    Ok(sets
                        .iter()
                        .map(|set| {
                            let mut full = (*set).clone();
                            full.extend(overrides.clone());
                            let (consulted, fingerprint) = reader.read(program, &full);
                            fingerprints.insert(full, fingerprint);
                            consulted
                        })
                        .collect())
                });
                let Ok(covering) = result;
                for set in covering.sets {
                    let mut full = set;
                    full.extend(overrides.clone());
                    if found[..global.len()].iter().any(|(known, _)| *known == full) {
                        continue;
                    }
                    let fingerprint = fingerprints.get(&full).copied();
                    found.push((full, fingerprint));
                }
                return (found, Some(covering.covered));
            }
            (found, None)
        })
        .collect();
    let covered = per_program.iter().filter_map(|(_, covered)| *covered).max();
    let mut summary = PlanSummary { covered, ..PlanSummary::default() };
    let mut pairs = Vec::new();
    let mut seen: std::collections::HashSet<Fingerprint> = std::collections::HashSet::new();
    for (&program, (found, _)) in runnable.iter().zip(per_program) {
        for (set, fingerprint) in found {
            summary.considered += 1;
            if let Some(fingerprint) = fingerprint {
                if !seen.insert(fingerprint) {
                    summary.identical += 1;
                    continue;
                }
                if let Some(shard) = shard
                    && !shard.keeps(&fingerprint)
                {
                    summary.other_shards += 1;
                    continue;
                }
            }
            let set_index = table.intern(set.clone(), || label_of(&set));
            pairs.push(Pair { program, set: set_index, fingerprint });
        }
    }
    (pairs, summary)
}
