//! The option space of a pack and the one way to name a point in it.
//!
//! A pack's options are the `#define` and `const` option lines of its shader files
//! ([`crate::option_lines`]), its profiles the `profile.<NAME>` entries of shaders.properties.
//! A [`Configuration`] names what a player runs: a profile, single option values, a dimension
//! and a loader. `validate` and `render` take the same `--profile`, `--set NAME=VALUE`,
//! `--dimension` and `--loader` and build one of these.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt;

use tidepack_glsl::preprocess::resolve_include;
use tidepack_glsl::{Code, Diagnostic, Location, terminal};

use crate::consts;
use crate::input::PackFiles;
use crate::loader::Loader;
use crate::macros::StandardMacros;
use crate::option_lines::{self, OptionKind, OptionSet, OptionValue};
use crate::properties::{self, Macros, Properties};

/// Options declared in the pack's shader sources (the first declaration of a name wins). A
/// `#define NAME` line is a switch when a file it is read with tests the name: every file
/// connected to it by `#include`s, in either direction, as Iris groups them (OptiFine reads
/// each program with its includes spliced in).
pub fn declared_options(pack: &PackFiles) -> BTreeMap<String, OptionKind> {
    let sources: Vec<(&String, &str)> = pack
        .texts
        .iter()
        .filter(|(path, _)| !(path.ends_with(".properties") || path.ends_with(".lang") || path.ends_with(".txt")))
        .map(|(path, text)| (path, &**text))
        .collect();
    let components = include_components(&sources);
    let mut tested: BTreeMap<usize, BTreeSet<String>> = BTreeMap::new();
    for (i, (_, text)) in sources.iter().enumerate() {
        tested.entry(components[i]).or_default().extend(option_lines::tested_names(text));
    }
    let mut found = BTreeMap::new();
    for (i, (_, text)) in sources.iter().enumerate() {
        for decl in option_lines::scan_tested(text, &tested[&components[i]]) {
            found.entry(decl.name).or_insert(decl.kind);
        }
    }
    found
}

/// For each source, the smallest index of the sources its `#include "…"` lines connect it to.
fn include_components(sources: &[(&String, &str)]) -> Vec<usize> {
    let index: BTreeMap<&str, usize> = sources.iter().enumerate().map(|(i, (path, _))| (path.as_str(), i)).collect();
    let mut parent: Vec<usize> = (0..sources.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (i, (path, text)) in sources.iter().enumerate() {
        for line in text.lines() {
            let Some(target) = line.trim().strip_prefix("#include").and_then(|r| r.trim().strip_prefix('"')).and_then(|r| r.split('"').next()) else {
                continue;
            };
            if let Ok(resolved) = resolve_include(path, target)
                && let Some(&j) = index.get(resolved.as_str())
            {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    (0..sources.len()).map(|i| root(&mut parent, i)).collect()
}

/// The macros a properties file's conditionals see under `set`: the loader's standard macros
/// and every `#define` option that is on (switches) or has a value (`const` options are no
/// macros).
pub fn property_macros(standard: &StandardMacros, declared: &BTreeMap<String, OptionKind>, set: &OptionSet) -> Macros {
    let mut macros: Macros = standard.property_definitions().into_iter().collect();
    for (name, kind) in declared.iter().filter(|(name, _)| !consts::OPTION_NAMES.contains(&name.as_str())) {
        match set.get(name).cloned().unwrap_or_else(|| kind.default_value()) {
            OptionValue::Switch(true) => {
                macros.insert(name.clone(), String::new());
            }
            OptionValue::Switch(false) => {}
            OptionValue::Value(v) => {
                macros.insert(name.clone(), v);
            }
        }
    }
    macros
}

/// A properties file's `text` read under `set` as the loader of `standard` reads it, with its
/// macros.
pub fn read_properties(text: &str, standard: &StandardMacros, declared: &BTreeMap<String, OptionKind>, set: &OptionSet) -> Properties {
    let loader = if standard.iris_version.is_some() { Loader::Iris } else { Loader::default() };
    Properties::parse(text, &property_macros(standard, declared, set), loader)
}

/// The pack's shaders.properties read under `set` with `standard`'s macros (empty when the pack
/// has none).
pub fn pack_properties(pack: &PackFiles, standard: &StandardMacros, set: &OptionSet) -> Properties {
    let text = pack.texts.get(properties::PATH).map_or("", |t| &**t);
    read_properties(text, standard, &declared_options(pack), set)
}

/// The names of a pack's profiles, each with the line its entry starts on.
pub fn profiles(props: &Properties) -> BTreeMap<String, u32> {
    props.with_prefix("profile.").map(|(name, entry)| (name.to_string(), entry.line)).collect()
}

/// Most option entries the profiles of a pack may resolve to, all profiles together: each
/// profile holds a copy of the sets of the profiles it names, so a long chain of large
/// profiles would otherwise grow with the square of its length.
pub const MAX_PROFILE_ENTRIES: usize = 1_000_000;

/// The option set of profile `name`: its own entries, and those of the profiles it names, in
/// the order written (a later value wins). `options` are the pack's declared options; entries
/// naming other things are reported as warnings. A cycle is an error naming it.
pub fn profile_set(props: &Properties, name: &str, options: &BTreeMap<String, OptionKind>) -> Result<(OptionSet, Vec<Diagnostic>), Diagnostic> {
    ProfileResolver::new(props, options).resolve(name)
}

/// Resolves profiles, each once however many profiles name it and in whatever order they
/// are asked for, without recursion, so chains of any depth cost their size.
pub struct ProfileResolver<'p> {
    entries: HashMap<&'p str, (&'p str, u32)>,
    options: &'p BTreeMap<String, OptionKind>,
    resolved: HashMap<&'p str, OptionSet>,
    /// Profiles whose resolution failed, with the error.
    failed: HashMap<&'p str, Diagnostic>,
    entries_resolved: usize,
}

impl<'p> ProfileResolver<'p> {
    pub fn new(props: &'p Properties, options: &'p BTreeMap<String, OptionKind>) -> Self {
        let entries = props.with_prefix("profile.").map(|(n, e)| (n, (e.value.as_str(), e.line))).collect();
        ProfileResolver { entries, options, resolved: HashMap::new(), failed: HashMap::new(), entries_resolved: 0 }
    }

    /// Profile `name`'s set and the warnings its own entries and those of the profiles first
    /// resolved here give (a profile's warnings are given once, by the first call that
    /// resolves it).
    pub fn resolve(&mut self, name: &str) -> Result<(OptionSet, Vec<Diagnostic>), Diagnostic> {
        let Some((&name, _)) = self.entries.get_key_value(name) else {
            let mut known: Vec<&str> = self.entries.keys().copied().collect();
            known.sort_unstable();
            return Err(Diagnostic::error(
                Code::Profile,
                format!(
                "no profile `{}` in shaders.properties (profiles: {})",
                terminal::line(name),
                if known.is_empty() { "none".into() } else { known.join(", ") }
            ),
                None,
            ));
        };
        let mut warnings = Vec::new();
        // Depth-first with an explicit stack; `path` holds the profiles being resolved.
        let mut path: Vec<&str> = vec![name];
        while let Some(&current) = path.last() {
            if let Some(error) = self.failed.get(current) {
                let error = error.clone();
                for p in path {
                    self.failed.insert(p, error.clone());
                }
                return Err(error);
            }
            let (value, line) = self.entries[current];
            let at = Some(Location::line(properties::PATH, line));
            let pending = value.split_whitespace().filter_map(|e| e.strip_prefix("profile.")).find(|other| !self.resolved.contains_key(other));
            let error = match pending {
                Some(other) if path.contains(&other) => {
                    let cycle: Vec<&str> = path[path.iter().position(|p| *p == other).unwrap_or(0)..].to_vec();
                    Some(Diagnostic::error(Code::Profile, format!("profile cycle: {} -> {other}", cycle.join(" -> ")), at))
                }
                Some(other) => match self.entries.get_key_value(other) {
                    Some((&other, _)) => {
                        path.push(other);
                        None
                    }
                    None => Some(Diagnostic::error(
                        Code::Profile,
                        format!("profile `{current}` names profile `{other}`, which shaders.properties does not define"),
                        at,
                    )),
                },
                None => {
                    let set = own_entries(current, value, line, self.options, &self.resolved, &mut warnings);
                    self.entries_resolved += set.len();
                    if self.entries_resolved > MAX_PROFILE_ENTRIES {
                        Some(Diagnostic::error(
                            Code::Budget,
                            format!("the profiles resolve to more than {MAX_PROFILE_ENTRIES} option entries in all (the budget for profiles); profile `{current}` is not read"),
                            at,
                        ))
                    } else {
                        self.resolved.insert(current, set);
                        path.pop();
                        None
                    }
                }
            };
            if let Some(error) = error {
                for p in path {
                    self.failed.insert(p, error.clone());
                }
                return Err(error);
            }
        }
        Ok((self.resolved[name].clone(), warnings))
    }
}

/// The set one profile's entries make, the profiles it names already in `resolved`.
fn own_entries(
    name: &str,
    value: &str,
    line: u32,
    options: &BTreeMap<String, OptionKind>,
    resolved: &HashMap<&str, OptionSet>,
    warnings: &mut Vec<Diagnostic>,
) -> OptionSet {
    let at = || Some(Location::line(properties::PATH, line));
    let mut set = OptionSet::new();
    for entry in value.split_whitespace() {
        if let Some(other) = entry.strip_prefix("profile.") {
            set.extend(resolved.get(other).cloned().unwrap_or_default());
            continue;
        }
        if entry.starts_with("!program.") || entry.starts_with("program.") {
            continue;
        }
        let (option, value) = match entry.split_once([':', '=']) {
            Some((o, v)) => (o, Some(v)),
            None => (entry.trim_start_matches('!'), None),
        };
        match (options.get(option), value) {
            (Some(OptionKind::Switch { .. }), None) => {
                set.insert(option.to_string(), OptionValue::Switch(!entry.starts_with('!')));
            }
            (Some(OptionKind::Value { values, .. }), Some(v)) => {
                if !values.iter().any(|x| x == v) {
                    warnings.push(Diagnostic::warning(
                        Code::Profile,
                        format!("profile `{name}` sets {option} to `{v}`, which is not among its values [{}]", values.join(" ")),
                        at(),
                    ));
                }
                set.insert(option.to_string(), OptionValue::Value(v.to_string()));
            }
            (Some(_), _) => warnings.push(Diagnostic::warning(
                Code::Profile,
                format!("profile `{name}`: `{entry}` does not match how {option} is declared (switch or value)"),
                at(),
            )),
            (None, _) => {
                warnings.push(Diagnostic::warning(Code::Profile, format!("profile `{name}` sets `{option}`, which no shader file declares as an option"), at()))
            }
        }
    }
    set
}

/// The options a player can change in the shader options menu: the names the `screen` and
/// `screen.<name>` entries list, or every option when a list holds `*` (the options no other
/// screen shows) or when there is no `screen` entry at all (OptiFine then lists every option
/// on its main screen). An option on no screen keeps its default for players.
pub fn menu_options(props: &Properties, declared: &BTreeMap<String, OptionKind>) -> BTreeMap<String, OptionKind> {
    let Some(main) = props.get("screen") else { return declared.clone() };
    let lists = std::iter::once(main.value.as_str()).chain(
        props.with_prefix("screen.").filter(|(rest, _)| *rest != "columns" && !rest.ends_with(".columns")).map(|(_, e)| e.value.as_str()),
    );
    let mut shown: BTreeSet<&str> = BTreeSet::new();
    for list in lists {
        for word in list.split_whitespace() {
            if word == "*" {
                return declared.clone();
            }
            shown.insert(word);
        }
    }
    declared.iter().filter(|(name, _)| shown.contains(name.as_str())).map(|(k, v)| (k.clone(), v.clone())).collect()
}

/// Which world folder a player is in (the overworld by default): `world0`, `world-1` (the
/// nether), `world1` (the end) or a modded dimension's `worldN`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Dimension(String);

impl Default for Dimension {
    fn default() -> Dimension {
        Dimension("world0".into())
    }
}

impl Dimension {
    /// The folder name, `world0`, `world-1`, `world1`, …
    pub fn folder(&self) -> &str {
        &self.0
    }

    /// Reads `overworld`, `nether`, `end` or a folder name (`world7`).
    pub fn parse(text: &str) -> Result<Dimension, String> {
        let folder = match text {
            "overworld" => "world0",
            "nether" => "world-1",
            "end" => "world1",
            other if crate::programs::is_world_folder(other) => other,
            other => return Err(format!("unknown dimension `{other}`: overworld, nether, end or a world folder such as world7")),
        };
        Ok(Dimension(folder.to_string()))
    }
}

impl fmt::Display for Dimension {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.folder() {
            "world0" => f.write_str("overworld"),
            "world-1" => f.write_str("nether"),
            "world1" => f.write_str("end"),
            other => f.write_str(other),
        }
    }
}

/// What a player runs: the option values (a profile, then single options), the dimension and
/// the loader.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Configuration {
    pub profile: Option<String>,
    /// `NAME` → value as written (`on`/`off`/`true`/`false` for switches), in order.
    pub options: Vec<(String, String)>,
    pub dimension: Dimension,
    pub loader: Loader,
    /// Distant Horizons beside Iris: `DISTANT_HORIZONS` is defined and Iris runs the `dh_*`
    /// programs.
    pub distant_horizons: bool,
}

impl Configuration {
    /// The macros the loader defines under this configuration.
    pub fn standard_macros(&self) -> StandardMacros {
        StandardMacros { distant_horizons: self.distant_horizons, ..StandardMacros::for_loader(self.loader) }
    }

    /// The option set this configuration means for a pack with `declared` options and
    /// properties `props`: the profile's values, then each single option. An unknown profile
    /// or option, or a value the option does not offer, is an error naming what there is.
    pub fn option_set(&self, props: &Properties, declared: &BTreeMap<String, OptionKind>) -> Result<(OptionSet, Vec<Diagnostic>), String> {
        let (mut set, warnings) = match &self.profile {
            Some(name) => profile_set(props, name, declared).map_err(|d| d.message)?,
            None => (OptionSet::new(), Vec::new()),
        };
        for (name, value) in &self.options {
            let kind = declared.get(name).ok_or_else(|| {
                let known: Vec<&str> = declared.keys().map(String::as_str).collect();
                let known = if known.is_empty() { "none".to_string() } else { known.join(", ") };
                format!("the pack has no option {}; its options: {known}", terminal::line(name))
            })?;
            let parsed = match kind {
                OptionKind::Switch { .. } => match value.as_str() {
                    "on" | "true" | "1" => OptionValue::Switch(true),
                    "off" | "false" | "0" => OptionValue::Switch(false),
                    _ => return Err(format!("{name} is a switch: set it to on or off, not {}", terminal::line(value))),
                },
                OptionKind::Value { values, .. } if values.contains(value) => OptionValue::Value(value.clone()),
                OptionKind::Value { values, .. } => {
                    return Err(format!("{name} takes one of {}, not {}", values.join(", "), terminal::line(value)));
                }
            };
            set.insert(name.clone(), parsed);
        }
        Ok((set, warnings))
    }

    /// [`Configuration::option_set`] for `pack`, its properties read under its defaults with the
    /// configuration's loader's macros.
    pub fn option_set_of(&self, pack: &PackFiles) -> Result<(OptionSet, Vec<Diagnostic>), String> {
        let props = pack_properties(pack, &StandardMacros::for_loader(self.loader), &OptionSet::new());
        self.option_set(&props, &declared_options(pack))
    }

    /// The command-line arguments that name this configuration
    /// (`--profile LOW --set BLOOM=off --dimension nether --loader iris`); empty for the defaults.
    pub fn arguments(&self) -> String {
        let mut words = Vec::new();
        if let Some(p) = &self.profile {
            words.push(format!("--profile {p}"));
        }
        for (name, value) in &self.options {
            words.push(format!("--set {name}={value}"));
        }
        if self.dimension != Dimension::default() {
            words.push(format!("--dimension {}", self.dimension));
        }
        if self.loader != Loader::default() {
            words.push(format!("--loader {}", self.loader));
        }
        words.join(" ")
    }
}

/// `NAME=VALUE` arguments of `--set` as pairs; an error names a malformed one.
pub fn parse_assignments(arguments: &[String]) -> Result<Vec<(String, String)>, String> {
    arguments
        .iter()
        .map(|assignment| match assignment.split_once('=') {
            Some((name, value)) if !name.trim().is_empty() => Ok((name.trim().to_string(), value.trim().to_string())),
            _ => Err(format!("--set takes OPTION=VALUE, not `{}`", assignment.escape_debug())),
        })
        .collect()
}

#[cfg(test)]
mod menu_tests {
    use super::*;

    #[test]
    fn the_menu_shows_what_the_screens_list() {
        let declared: BTreeMap<String, OptionKind> =
            ["BLOOM", "FSH", "FOG", "SHADOWS"].iter().map(|n| (n.to_string(), OptionKind::Switch { default: true })).collect();
        let names = |props: &str| menu_options(&Properties::parse_plain(props), &declared).into_keys().collect::<Vec<_>>();
        assert_eq!(names(""), ["BLOOM", "FOG", "FSH", "SHADOWS"], "no screen: every option");
        assert_eq!(names("screen = BLOOM [ATMOSPHERE] <empty>\nscreen.ATMOSPHERE = FOG\nscreen.columns = 2\n"), ["BLOOM", "FOG"]);
        assert_eq!(names("screen = BLOOM [MORE]\nscreen.MORE = *\n"), ["BLOOM", "FOG", "FSH", "SHADOWS"]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_switch_is_tested_anywhere_its_includes_connect_it() {
        let files = [
            ("lib/settings.glsl", "//#define GODRAYS\n#define LONELY\n"),
            ("lib/rays.glsl", "#ifdef GODRAYS\n#endif\n"),
            ("lib/bloom.frag", "//#define BLOOM\n"),
            ("composite.fsh", "#include \"/lib/settings.glsl\"\n#include \"lib/rays.glsl\"\n#include \"lib/bloom.frag\"\n#ifdef BLOOM\n#endif\nvoid main() {}\n"),
            ("final.fsh", "#ifdef LONELY\n#endif\nvoid main() {}\n"),
        ];
        let pack = crate::input::pack_from_memory("p/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
        let declared = declared_options(&pack);
        assert_eq!(declared.get("GODRAYS"), Some(&OptionKind::Switch { default: false }), "{declared:?}");
        // Included files of any GLSL extension are read for options too.
        assert_eq!(declared.get("BLOOM"), Some(&OptionKind::Switch { default: false }), "{declared:?}");
        // final.fsh tests LONELY but includes nothing that declares it.
        assert!(!declared.contains_key("LONELY"), "{declared:?}");
    }

    fn options() -> BTreeMap<String, OptionKind> {
        [
            ("SHADOWS".to_string(), OptionKind::Switch { default: true }),
            ("WAVES".to_string(), OptionKind::Switch { default: false }),
            ("QUALITY".to_string(), OptionKind::Value { default: "2".into(), values: vec!["1".into(), "2".into()] }),
        ]
        .into()
    }

    #[test]
    fn profiles_follow_their_entries_in_order() {
        let props = Properties::parse_plain("profile.LOW=!SHADOWS QUALITY:1 \\\n  profile.BASE\nprofile.BASE=WAVES\nprofile.HIGH=profile.LOW QUALITY=2 SHADOWS\n");
        let (set, warnings) = profile_set(&props, "LOW", &options()).unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(set["SHADOWS"], OptionValue::Switch(false));
        assert_eq!(set["WAVES"], OptionValue::Switch(true));
        assert_eq!(set["QUALITY"], OptionValue::Value("1".into()));
        let (high, _) = profile_set(&props, "HIGH", &options()).unwrap();
        assert_eq!(high["QUALITY"], OptionValue::Value("2".into()));
        assert_eq!(high["SHADOWS"], OptionValue::Switch(true));
        assert!(profile_set(&props, "NONE", &options()).is_err());
    }

    #[test]
    fn every_profile_of_a_deep_chain_resolves_with_the_work_shared() {
        let chain: String = (0..20_000).map(|i| format!("profile.P{i}=profile.P{} SHADOWS\n", i + 1)).collect::<String>() + "profile.P20000=!WAVES\n";
        let props = Properties::parse_plain(&chain);
        let options = options();
        let mut resolver = ProfileResolver::new(&props, &options);
        for name in profiles(&props).keys() {
            let (set, _) = resolver.resolve(name).unwrap();
            assert_eq!(set.get("WAVES"), Some(&OptionValue::Switch(false)), "{name}");
        }
    }

    #[test]
    fn a_broken_profile_is_one_error_for_every_profile_naming_it() {
        let props = Properties::parse_plain("profile.A=profile.B\nprofile.B=profile.C\nprofile.D=profile.B\n");
        let options = options();
        let mut resolver = ProfileResolver::new(&props, &options);
        let errors: Vec<Diagnostic> = ["A", "B", "D"].iter().map(|p| resolver.resolve(p).unwrap_err()).collect();
        assert!(errors.iter().all(|e| *e == errors[0]), "{errors:?}");
        assert!(errors[0].message.contains("`B` names profile `C`"), "{}", errors[0].message);
    }

    #[test]
    fn profiles_past_the_budget_are_refused_naming_it() {
        let options: BTreeMap<String, OptionKind> =
            (0..2_000).map(|i| (format!("O{i}"), OptionKind::Switch { default: false })).collect();
        let all: String = (0..2_000).map(|i| format!(" O{i}")).collect();
        let chain: String = (0..600).map(|i| format!("profile.P{i}=profile.P{}{all}\n", i + 1)).collect::<String>() + "profile.P600=\n";
        let props = Properties::parse_plain(&chain);
        let err = profile_set(&props, "P0", &options).unwrap_err();
        assert!(err.message.contains("budget for profiles"), "{}", err.message);
    }

    #[test]
    fn cycles_and_unknown_options_are_reported() {
        let props = Properties::parse_plain("profile.A=profile.B\nprofile.B=profile.A TYPO\n");
        let err = profile_set(&props, "A", &BTreeMap::new()).unwrap_err();
        assert!(err.message.contains("cycle") && err.message.contains("A -> B -> A"), "{err}");
        let props = Properties::parse_plain("profile.A=TYPO\n");
        let (_, warnings) = profile_set(&props, "A", &BTreeMap::new()).unwrap();
        assert_eq!(warnings[0].location.as_ref().unwrap().line, 1);
        let props = Properties::parse_plain("profile.A=profile.MISSING\n");
        assert!(profile_set(&props, "A", &BTreeMap::new()).unwrap_err().message.contains("MISSING"));
    }

    #[test]
    fn deep_chains_and_many_paths_resolve_once_each() {
        let mut chain = String::new();
        for i in 0..20_000 {
            chain.push_str(&format!("profile.P{i}=profile.P{} WAVES\n", i + 1));
        }
        chain.push_str("profile.P20000=SHADOWS\n");
        let (set, _) = profile_set(&Properties::parse_plain(&chain), "P0", &options()).unwrap();
        assert_eq!(set.len(), 2);
        // Forty levels, each naming both profiles of the next: 2^40 paths, 80 profiles.
        let mut lattice = String::new();
        for i in 0..40 {
            lattice.push_str(&format!("profile.A{i}=profile.A{n} profile.B{n}\nprofile.B{i}=profile.A{n} profile.B{n}\n", n = i + 1));
        }
        lattice.push_str("profile.A40=WAVES\nprofile.B40=!SHADOWS\n");
        let (set, _) = profile_set(&Properties::parse_plain(&lattice), "A0", &options()).unwrap();
        assert_eq!(set["WAVES"], OptionValue::Switch(true));
    }

    #[test]
    fn a_configuration_names_its_values_and_refuses_unknown_ones() {
        let props = Properties::parse_plain("profile.LOW=QUALITY:1 !SHADOWS\n");
        let config = |profile: Option<&str>, options: &[(&str, &str)]| Configuration {
            profile: profile.map(str::to_string),
            options: options.iter().map(|(n, v)| (n.to_string(), v.to_string())).collect(),
            ..Configuration::default()
        };
        let (set, _) = config(Some("LOW"), &[("QUALITY", "2"), ("SHADOWS", "on")]).option_set(&props, &options()).unwrap();
        assert_eq!(set["QUALITY"], OptionValue::Value("2".into()));
        assert_eq!(set["SHADOWS"], OptionValue::Switch(true));
        let unknown = config(None, &[("NOPE", "1")]).option_set(&props, &options()).unwrap_err();
        assert!(unknown.contains("no option NOPE") && unknown.contains("QUALITY"), "{unknown}");
        assert!(config(None, &[("QUALITY", "7")]).option_set(&props, &options()).unwrap_err().contains("one of 1, 2"));
        assert!(config(None, &[("SHADOWS", "maybe")]).option_set(&props, &options()).is_err());
        assert!(config(Some("ULTRA"), &[]).option_set(&props, &options()).unwrap_err().contains("ULTRA"));
        let mut nether = config(Some("LOW"), &[("WAVES", "on")]);
        nether.dimension = Dimension::parse("nether").unwrap();
        nether.loader = Loader::Iris;
        assert_eq!(nether.arguments(), "--profile LOW --set WAVES=on --dimension nether --loader iris");
    }

    #[test]
    fn a_pack_files_configuration_reads_its_profiles_and_options() {
        let files = crate::input::pack_from_memory(
            "test/shaders/",
            [
                ("composite.fsh".to_string(), b"#define MODE 1 // [1 2 3]\n#define GLOW\n#ifdef GLOW\n#endif\nvoid main() {}\n".to_vec()),
                ("shaders.properties".to_string(), b"#ifdef IS_IRIS\nprofile.LOW=MODE:3\n#else\nprofile.LOW=MODE:2 !GLOW\n#endif\n".to_vec()),
            ],
        );
        let low = Configuration { profile: Some("LOW".into()), ..Configuration::default() };
        let (set, _) = low.option_set_of(&files).unwrap();
        assert_eq!(set.get("MODE"), Some(&OptionValue::Value("2".into())));
        assert_eq!(set.get("GLOW"), Some(&OptionValue::Switch(false)));
        let iris = Configuration { loader: Loader::Iris, ..low };
        assert_eq!(iris.option_set_of(&files).unwrap().0.get("MODE"), Some(&OptionValue::Value("3".into())));
    }

    #[test]
    fn property_macros_hold_the_standard_macros_and_the_options_in_force() {
        let set: OptionSet = [("WAVES".to_string(), OptionValue::Switch(true)), ("SHADOWS".to_string(), OptionValue::Switch(false))].into();
        let macros = property_macros(&StandardMacros::default(), &options(), &set);
        assert_eq!(macros.get("WAVES").map(String::as_str), Some(""));
        assert!(!macros.contains_key("SHADOWS"));
        assert_eq!(macros.get("QUALITY").map(String::as_str), Some("2"));
        assert!(macros.contains_key("MC_VERSION"));
    }

    #[test]
    fn dimensions_by_name_and_folder() {
        assert_eq!(Dimension::parse("end").unwrap().folder(), "world1");
        assert_eq!(Dimension::parse("world7").unwrap().to_string(), "world7");
        assert_eq!(Dimension::default().folder(), "world0");
        assert!(Dimension::parse("moon").unwrap_err().contains("overworld, nether, end"));
    }
}
