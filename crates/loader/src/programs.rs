//! Which files of a pack are programs, which loader runs them, in which world folder, and the
//! fallbacks OptiFine follows when a program's files are absent.

use std::collections::BTreeMap;

use tidepack_glsl::Stage;

use crate::loader::Loader;
use crate::option_lines::{OptionKind, OptionSet, OptionValue};
use crate::option_space::Dimension;
use crate::properties::Properties;

/// OptiFine's gbuffers programs and the program each falls back to when its files are absent
/// (`None`: no fallback, fixed-function rendering).
pub const GBUFFERS: [(&str, Option<&str>); 22] = [
    ("gbuffers_basic", None),
    ("gbuffers_line", Some("gbuffers_basic")),
    ("gbuffers_textured", Some("gbuffers_basic")),
    ("gbuffers_textured_lit", Some("gbuffers_textured")),
    ("gbuffers_skybasic", Some("gbuffers_basic")),
    ("gbuffers_skytextured", Some("gbuffers_textured")),
    ("gbuffers_clouds", Some("gbuffers_textured")),
    ("gbuffers_terrain", Some("gbuffers_textured_lit")),
    ("gbuffers_damagedblock", Some("gbuffers_terrain")),
    ("gbuffers_block", Some("gbuffers_terrain")),
    ("gbuffers_beaconbeam", Some("gbuffers_textured")),
    ("gbuffers_item", Some("gbuffers_textured_lit")),
    ("gbuffers_entities", Some("gbuffers_textured_lit")),
    ("gbuffers_entities_glowing", Some("gbuffers_entities")),
    ("gbuffers_armor_glint", Some("gbuffers_textured")),
    ("gbuffers_spidereyes", Some("gbuffers_textured")),
    ("gbuffers_hand", Some("gbuffers_textured_lit")),
    ("gbuffers_weather", Some("gbuffers_textured_lit")),
    ("gbuffers_water", Some("gbuffers_terrain")),
    ("gbuffers_hand_water", Some("gbuffers_hand")),
    ("shadow", None),
    ("final", None),
];

/// Fullscreen passes with numbered variants `name`, `name1` … `name99`.
const NUMBERED: [&str; 4] = ["shadowcomp", "prepare", "deferred", "composite"];

/// Programs only Iris runs (with why), and OptiFine names it never runs.
const IRIS_ONLY: [&str; 9] = [
    "gbuffers_terrain_solid",
    "gbuffers_terrain_cutout",
    "gbuffers_particles",
    "gbuffers_particles_translucent",
    "gbuffers_entities_translucent",
    "gbuffers_block_translucent",
    "gbuffers_lightning",
    "shadow_entities_translucent",
    "gbuffers_line_translucent",
];

/// Shadow programs Iris runs for parts of the shadow pass (each falling back to `shadow`).
const IRIS_SHADOW: [&str; 6] = ["shadow_solid", "shadow_cutout", "shadow_water", "shadow_entities", "shadow_lightning", "shadow_block"];

/// Whether `loader` runs a program of this name, as far as `validate` checks it: OptiFine's
/// programs, and under Iris also its finer gbuffers and shadow programs and its `begin`/`setup`
/// compute passes (Iris's `ProgramId`). Distant Horizons' `dh_*` programs run only where the
/// mod is installed: [`runs_with`].
pub fn runs(name: &str, loader: Loader) -> bool {
    run_by(name) == RunBy::OptiFine
        || (loader == Loader::Iris
            && (IRIS_ONLY.contains(&name) || IRIS_SHADOW.contains(&name) || numbered(name, "begin") || numbered(name, "setup")))
}

/// Whether `program` draws the world and binds its textures as gbuffers programs do (the atlas,
/// lightmap, normals and specular maps on the low units): gbuffers_*, `shadow` and Iris's
/// shadow_solid, shadow_water, … , and Distant Horizons' dh_*. Not shadowcomp, a full-screen pass.
pub fn binds_as_gbuffers(program: &str) -> bool {
    program.starts_with("gbuffers_") || program == "shadow" || program.starts_with("shadow_") || program.starts_with("dh_")
}

/// The programs Iris runs for Distant Horizons' LODs when the mod is installed.
pub const DISTANT_HORIZONS_PROGRAMS: [&str; 4] = ["dh_terrain", "dh_water", "dh_shadow", "dh_generic"];

/// [`runs`], and with Distant Horizons beside Iris also its `dh_*` programs.
pub fn runs_with(name: &str, loader: Loader, distant_horizons: bool) -> bool {
    runs(name, loader) || (loader == Loader::Iris && distant_horizons && DISTANT_HORIZONS_PROGRAMS.contains(&name))
}

/// A stage's text with what the loader declares in it: Iris's `dhMaterialId` in the vertex
/// stage of a Distant Horizons program.
pub fn with_loader_declarations<'t>(program: &str, vertex: bool, text: &'t str) -> std::borrow::Cow<'t, str> {
    if vertex && DISTANT_HORIZONS_PROGRAMS.contains(&program) && uses_undeclared_dh_material_id(text) {
        declare_before_code(text, "int dhMaterialId;")
    } else {
        std::borrow::Cow::Borrowed(text)
    }
}

/// Whether `text` uses `dhMaterialId` (Distant Horizons' material of the vertex, one of the
/// `DH_BLOCK_*` values) without declaring it: Iris declares it in the vertex stage of every
/// `dh_*` program, and a pack uses it undeclared.
pub fn uses_undeclared_dh_material_id(text: &str) -> bool {
    const NAME: &str = "dhMaterialId";
    let is_word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut used = false;
    let mut declared = false;
    for (at, _) in text.match_indices(NAME) {
        let before = &text[..at];
        if before.ends_with(is_word) || text[at + NAME.len()..].starts_with(is_word) {
            continue;
        }
        used = true;
        // `int dhMaterialId`: a type, whitespace, the name.
        let spaced = before.trim_end_matches([' ', '\t']);
        declared |= spaced.len() < before.len() && ["int", "uint", "float"].iter().any(|ty| {
            spaced.strip_suffix(ty).is_some_and(|rest| !rest.ends_with(is_word))
        });
    }
    used && !declared
}

/// `text` (a stage as the driver or naga gets it) with `declaration` put before its first line
/// of code outside any `#if`, on that line so that every line keeps its number; unchanged when
/// it has no such line.
pub fn declare_before_code<'t>(text: &'t str, declaration: &str) -> std::borrow::Cow<'t, str> {
    let mut depth = 0usize;
    let mut in_comment = false;
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim();
        let directive = trimmed.strip_prefix('#').map(str::trim_start);
        match directive {
            Some(d) if d.starts_with("if") => depth += 1,
            Some(d) if d.starts_with("endif") => depth = depth.saturating_sub(1),
            _ => {}
        }
        let code = directive.is_none() && !in_comment && !trimmed.is_empty() && !trimmed.starts_with("//") && !trimmed.starts_with("/*");
        if trimmed.starts_with("/*") && !trimmed.contains("*/") {
            in_comment = true;
        } else if in_comment && trimmed.contains("*/") {
            in_comment = false;
        }
        if code && depth == 0 {
            return std::borrow::Cow::Owned(format!("{}{declaration} {}", &text[..offset], &text[offset..]));
        }
        offset += line.len();
    }
    std::borrow::Cow::Borrowed(text)
}

/// Whether `name` is `base` or `base1` … `base99`.
fn numbered(name: &str, base: &str) -> bool {
    name.strip_prefix(base).is_some_and(|n| n.is_empty() || (n.len() <= 2 && n.parse::<u32>().is_ok_and(|v| v >= 1 && !n.starts_with('0'))))
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RunBy {
    /// OptiFine runs it.
    OptiFine,
    /// Another loader runs it; OptiFine ignores the files. The text says which and why.
    Other(String),
    /// No loader runs a program of this name.
    Unknown,
}

/// Who runs a program of this name.
pub fn run_by(name: &str) -> RunBy {
    if GBUFFERS.iter().any(|(n, _)| *n == name) {
        return RunBy::OptiFine;
    }
    if NUMBERED.iter().any(|b| numbered(name, b)) {
        return RunBy::OptiFine;
    }
    if name.starts_with("dh_") {
        return RunBy::Other("Distant Horizons (through Iris)".into());
    }
    if name.starts_with("voxy") {
        return RunBy::Other("Voxy (through Iris)".into());
    }
    if numbered(name, "begin") || numbered(name, "setup") || IRIS_ONLY.contains(&name) {
        return RunBy::Other("Iris".into());
    }
    if matches!(name, "shadow_solid" | "shadow_cutout") {
        return RunBy::Other("nobody: OptiFine reserves the name but never runs it".into());
    }
    RunBy::Unknown
}

/// The program OptiFine runs for `name` in a world whose programs are `present`, following
/// the fallbacks; `None` when it runs none.
pub fn effective_program<'a>(name: &'a str, present: &dyn Fn(&str) -> bool) -> Option<&'a str> {
    let mut current = name;
    for _ in 0..GBUFFERS.len() {
        if present(current) {
            return Some(current);
        }
        current = GBUFFERS.iter().find(|(n, _)| *n == current)?.1?;
    }
    None
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Program {
    /// `""` for the shaders folder itself, else `world0`, `world-1`, …
    pub world: String,
    pub name: String,
    /// Stage files (paths relative to `shaders/`), vertex first.
    pub stages: Vec<(Stage, String)>,
    /// Geometry and tessellation files (`.gsh`, `.tcs`, `.tes`), which naga cannot read: they
    /// are preprocessed, and compiled by the driver with `--driver`.
    pub other_stages: Vec<String>,
    /// Compute files (`name.csh`, `name_a.csh` … `name_z.csh`), in the order OptiFine runs them.
    pub compute: Vec<String>,
    pub run_by: RunBy,
}

impl Program {
    /// `world-1/gbuffers_water` or `composite`.
    pub fn id(&self) -> String {
        if self.world.is_empty() { self.name.clone() } else { format!("{}/{}", self.world, self.name) }
    }

    /// The first stage file: vertex, else any other.
    pub fn entry(&self) -> Option<&str> {
        self.stages.first().map(|s| s.1.as_str()).or(self.other_stages.first().map(String::as_str)).or(self.compute.first().map(String::as_str))
    }

    /// Whether the program has any stage file at all.
    pub fn has_stages(&self) -> bool {
        !self.stages.is_empty() || !self.other_stages.is_empty() || !self.compute.is_empty()
    }

    /// The geometry, tessellation control and tessellation evaluation files.
    pub fn geometry(&self) -> Option<&String> {
        self.other_stages.iter().find(|s| s.ends_with(".gsh"))
    }
    pub fn tess_control(&self) -> Option<&String> {
        self.other_stages.iter().find(|s| s.ends_with(".tcs"))
    }
    pub fn tess_evaluation(&self) -> Option<&String> {
        self.other_stages.iter().find(|s| s.ends_with(".tes"))
    }
}

/// World folders: `world0`, `world-1`, `world1`, `world7`, …
pub fn is_world_folder(name: &str) -> bool {
    name.strip_prefix("world").is_some_and(|n| n.strip_prefix('-').unwrap_or(n).parse::<u32>().is_ok())
}

/// The folder whose programs `loader` runs in `dimension` (`""`: the shaders folder itself),
/// `has_folder` telling which folders hold programs, `dimension_map` the pack's
/// `dimension.properties` as Iris reads it ([`dimension_map`]; empty without one).
///
/// OptiFine runs a dimension's world folder (`world-1/`; an empty one runs nothing), else the
/// shaders folder. Iris looks the dimension's id up in the map, which without a
/// `dimension.properties` holds the vanilla world folders the pack has (`world0/` also for every
/// other dimension): the folder found, where it holds programs, or else the one the map gives
/// every dimension (`*`), or the shaders folder.
pub fn world_folder(dimension: &Dimension, loader: Loader, has_folder: &dyn Fn(&str) -> bool, dimension_map: &[(String, String)]) -> String {
    let folder = dimension.folder();
    if loader != Loader::Iris {
        return if has_folder(folder) { folder.to_string() } else { String::new() };
    }
    let defaults: Vec<(String, String)>;
    let map = if dimension_map.is_empty() {
        defaults = [("minecraft:overworld", "world0"), ("*", "world0"), ("minecraft:the_nether", "world-1"), ("minecraft:the_end", "world1")]
            .into_iter()
            .filter(|(_, f)| has_folder(f))
            .map(|(id, f)| (id.to_string(), f.to_string()))
            .collect();
        &defaults
    } else {
        dimension_map
    };
    let mapped = |id: &str| map.iter().find(|(i, _)| i == id).map(|(_, f)| f.clone());
    let id = match folder {
        "world0" => Some("minecraft:overworld"),
        "world-1" => Some("minecraft:the_nether"),
        "world1" => Some("minecraft:the_end"),
        _ => None,
    };
    match id.and_then(mapped).filter(|f| has_folder(f)) {
        Some(found) => found,
        // A modded dimension (`world7`) with a folder of its own, as OptiFine names them.
        None if id.is_none() && has_folder(folder) => folder.to_string(),
        None => mapped("*").unwrap_or_default(),
    }
}

/// Iris's `dimension.properties`: each `dimension.<folder> = <id> <id> …` line as (id, folder),
/// ids namespaced (`minecraft:` where none is written), `*` for every other dimension.
pub fn dimension_map(text: &str) -> Vec<(String, String)> {
    let mut map = Vec::new();
    for line in text.lines().map(str::trim).filter(|l| !l.starts_with('#') && !l.starts_with('!')) {
        let Some((key, value)) = line.split_once(['=', ':']) else { continue };
        let Some(folder) = key.trim().strip_prefix("dimension.") else { continue };
        for id in value.split_whitespace() {
            let id = if id == "*" || id.contains(':') { id.to_string() } else { format!("minecraft:{id}") };
            map.push((id, folder.to_string()));
        }
    }
    map
}

/// Every program file of the pack's world folders (the root counts as one), grouped.
pub fn find_programs<'a>(paths: impl Iterator<Item = &'a String>) -> Vec<Program> {
    find_programs_in(paths, &is_world_folder)
}

/// [`find_programs`] where `is_world` tells which folders hold programs (Iris's
/// `dimension.properties` names folders of any name).
pub fn find_programs_in<'a>(paths: impl Iterator<Item = &'a String>, is_world: &dyn Fn(&str) -> bool) -> Vec<Program> {
    let mut found: BTreeMap<(String, String), Program> = BTreeMap::new();
    for path in paths {
        let (world, file) = match path.split_once('/') {
            None => ("", path.as_str()),
            Some((w, f)) if is_world(w) && !f.contains('/') => (w, f),
            _ => continue,
        };
        let Some((name, ext)) = file.rsplit_once('.') else { continue };
        let stage = match ext {
            "vsh" => Some(Stage::Vertex),
            "fsh" => Some(Stage::Fragment),
            "gsh" | "csh" | "tcs" | "tes" => None,
            _ => continue,
        };
        // Compute shaders may have suffixes `_a` … `_z`: the program is the base name.
        let base = if ext == "csh" {
            name.rsplit_once('_').filter(|(_, s)| s.len() == 1 && s.as_bytes()[0].is_ascii_lowercase()).map_or(name, |(b, _)| b)
        } else {
            name
        };
        let program = found.entry((world.to_string(), base.to_string())).or_insert_with(|| Program {
            world: world.to_string(),
            name: base.to_string(),
            stages: Vec::new(),
            other_stages: Vec::new(),
            compute: Vec::new(),
            run_by: run_by(base),
        });
        match stage {
            Some(stage) if base == name => program.stages.push((stage, path.clone())),
            _ if ext == "csh" => program.compute.push(path.clone()),
            _ if base == name => program.other_stages.push(path.clone()),
            // `name_a.vsh` and the like are no stage of any program.
            _ => {}
        }
    }
    let mut programs: Vec<Program> = found.into_values().collect();
    for p in &mut programs {
        p.stages.sort();
        p.other_stages.sort();
        // `composite.csh` runs first, then `composite_a.csh` … `composite_z.csh`.
        p.compute.sort();
    }
    programs
}

/// The programs of `world` (`world0`, or `""` for the shaders folder) that shaders.properties turns off with
/// `program.<name>.enabled` for `options` over the declared switches' defaults, and the
/// entries that could not be evaluated (those programs run).
pub fn disabled_programs(properties: &Properties, world: &str, declared: &BTreeMap<String, OptionKind>, options: &OptionSet) -> (Vec<String>, Vec<String>) {
    let switches: BTreeMap<String, bool> = declared
        .iter()
        .filter_map(|(name, kind)| match (options.get(name), kind) {
            (Some(OptionValue::Switch(on)), _) => Some((name.clone(), *on)),
            (_, OptionKind::Switch { default }) => Some((name.clone(), *default)),
            _ => None,
        })
        .collect();
    let mut disabled = Vec::new();
    let mut problems = Vec::new();
    for switch in crate::custom_uniforms::program_switches(properties) {
        let name = match switch.program.split_once('/') {
            Some((folder, name)) if folder == world => name,
            Some(_) => continue,
            None if world.is_empty() => switch.program.as_str(),
            None => continue,
        };
        match crate::custom_uniforms::evaluate_switch_expression(&switch, &switches) {
            Ok(true) => {}
            Ok(false) => disabled.push(name.to_string()),
            Err(e) => problems.push(format!("shaders.properties:{}: program.{}.enabled: {e} (the program runs)", switch.line, switch.program)),
        }
    }
    (disabled, problems)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dh_material_id_is_declared_before_the_first_code_where_it_is_used_undeclared() {
        let text = "#version 330 compatibility\n#extension GL_ARB_x : enable\n#ifdef A\nuniform int a;\n#endif\n/* a\nb */\nout float m;\nvoid main() { m = float(dhMaterialId == DH_BLOCK_WATER); }\n";
        let declared = with_loader_declarations("dh_water", true, text);
        assert_eq!(declared.lines().count(), text.lines().count());
        assert_eq!(declared.lines().nth(7), Some("int dhMaterialId; out float m;"));
        let own = "#version 330\nin int dhMaterialId;\nvoid main() { int m = dhMaterialId; }\n";
        assert_eq!(with_loader_declarations("dh_water", true, own), own);
        let unused = "#version 330\nvoid main() {}\n";
        assert_eq!(with_loader_declarations("dh_water", true, unused), unused);
    }

    #[test]
    fn classifies_program_names() {
        for name in ["gbuffers_water", "composite", "composite15", "deferred99", "shadowcomp1", "prepare", "final", "shadow"] {
            assert_eq!(run_by(name), RunBy::OptiFine, "{name}");
        }
        assert!(matches!(run_by("dh_terrain"), RunBy::Other(l) if l.contains("Distant Horizons")));
        assert!(matches!(run_by("begin1"), RunBy::Other(l) if l == "Iris"));
        assert!(matches!(run_by("gbuffers_particles"), RunBy::Other(_)));
        for name in ["composite100", "composite01", "gbuffers_wtaer", "common"] {
            assert_eq!(run_by(name), RunBy::Unknown, "{name}");
        }
    }

    #[test]
    fn fallbacks_follow_optifine() {
        let present = |p: &str| p == "gbuffers_textured" || p == "gbuffers_terrain";
        assert_eq!(effective_program("gbuffers_water", &present), Some("gbuffers_terrain"));
        assert_eq!(effective_program("gbuffers_hand", &present), Some("gbuffers_textured"));
        assert_eq!(effective_program("gbuffers_skybasic", &present), None);
        assert_eq!(effective_program("composite", &present), None);
    }

    #[test]
    fn each_dimension_runs_its_folder_or_the_shaders_folder() {
        let folders = |names: &'static [&'static str]| move |f: &str| names.contains(&f);
        let nether = Dimension::parse("nether").unwrap();
        let modded = Dimension::parse("world7").unwrap();
        let both = folders(&["world0", "world-1"]);
        let end = Dimension::parse("end").unwrap();
        assert_eq!(world_folder(&Dimension::default(), Loader::OptiFine1_21, &both, &[]), "world0");
        assert_eq!(world_folder(&nether, Loader::OptiFine1_21, &both, &[]), "world-1");
        assert_eq!(world_folder(&end, Loader::OptiFine1_21, &both, &[]), "");
        assert_eq!(world_folder(&modded, Loader::OptiFine1_21, &both, &[]), "");
        assert_eq!(world_folder(&modded, Loader::Iris, &both, &[]), "world0");
        assert_eq!(world_folder(&nether, Loader::Iris, &folders(&[]), &[]), "");
        // Iris runs world0/ in every dimension without a folder of its own.
        assert_eq!(world_folder(&end, Loader::Iris, &both, &[]), "world0");
    }

    /// Iris's dimension.properties (as yanis-dubois/BloomingLightShader maps its folders): each
    /// dimension's folder by its id, `*` for the others, and the shaders folder where a mapped
    /// folder is missing and nothing stands for `*`.
    #[test]
    fn iris_reads_the_dimension_folders_of_dimension_properties() {
        let text = "# folder of each dimension\ndimension.dimension_overworld = *\ndimension.dimension_nether = minecraft:the_nether nether\ndimension.dimension_end=the_end\n";
        let map = dimension_map(text);
        assert_eq!(map[0], ("*".to_string(), "dimension_overworld".to_string()));
        assert!(map.contains(&("minecraft:nether".to_string(), "dimension_nether".to_string())), "{map:?}");
        assert!(map.contains(&("minecraft:the_end".to_string(), "dimension_end".to_string())), "{map:?}");
        let folders = |names: &'static [&'static str]| move |f: &str| names.contains(&f);
        let all = folders(&["dimension_overworld", "dimension_nether", "dimension_end"]);
        assert_eq!(world_folder(&Dimension::default(), Loader::Iris, &all, &map), "dimension_overworld");
        assert_eq!(world_folder(&Dimension::parse("nether").unwrap(), Loader::Iris, &all, &map), "dimension_nether");
        assert_eq!(world_folder(&Dimension::parse("end").unwrap(), Loader::Iris, &folders(&["dimension_overworld"]), &map), "dimension_overworld");
        assert_eq!(world_folder(&Dimension::default(), Loader::OptiFine1_21, &all, &map), "");
        let nether_only = dimension_map("dimension.dimension_nether = the_nether\n");
        assert_eq!(world_folder(&Dimension::default(), Loader::Iris, &all, &nether_only), "");
    }

    #[test]
    fn groups_stages_by_world() {
        let paths: Vec<String> = [
            "gbuffers_water.vsh", "gbuffers_water.fsh", "world-1/gbuffers_water.fsh", "world-1/composite.gsh",
            "lib/water.glsl", "program/gbuffers_water.fsh", "world0/deep/x.fsh", "composite_a.csh",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let programs = find_programs(paths.iter());
        let ids: Vec<String> = programs.iter().map(Program::id).collect();
        assert_eq!(ids, ["composite", "gbuffers_water", "world-1/composite", "world-1/gbuffers_water"]);
        assert_eq!(programs[1].stages.len(), 2);
        assert_eq!(programs[0].compute, ["composite_a.csh"]);
        assert_eq!(programs[2].other_stages, ["world-1/composite.gsh"]);
    }
}
