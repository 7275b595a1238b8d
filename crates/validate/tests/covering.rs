//! `validate --covering`: each program under the covering sets of the options its text depends
//! on, each distinct program text validated once, across runs with `--cache` and across CI jobs
//! with `--shard`. Minimal packs of our own, each reproducing a pattern of released packs: a
//! mistake behind one toggle, one behind a pair of values, one behind an option that only
//! another option's branch tests.

use std::collections::BTreeSet;

use tidepack_loader::input::pack_from_memory;
use tidepack_validate::{Coverage, Options, Profiles, Report, SetsCovered, Shard, validate_pack};

const VERTEX: &str = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";

/// Settings shared by every program: two switches, a value option and one switch tested only
/// inside another's branch.
const SETTINGS: &str = "\
//#define GODRAYS // Light shafts
#define FOG // Distance fog
#define FOG_STYLE 1 // [1 2 3]
//#define FOG_NOISE // Only read where FOG_STYLE is 3
#ifdef GODRAYS
#endif
#ifdef FOG
#endif
#ifdef FOG_NOISE
#endif
";

/// Clean under the defaults. `GODRAYS` alone reads an undeclared name; `FOG_STYLE=2` with `FOG`
/// off calls a function with the wrong argument count; `FOG_NOISE` matters only under
/// `FOG_STYLE=3`, where it reads an undeclared name.
const COMPOSITE: &str = "#version 120
#include \"/settings.glsl\"
#ifdef GODRAYS
float rays() { return undeclaredStrength; }
#endif
float fog(float d) { return d; }
void main() {
    float f = 0.0;
#if FOG_STYLE == 2 && !defined FOG
    f = fog(1.0, 2.0);
#endif
#if FOG_STYLE == 3
  #ifdef FOG_NOISE
    f = noiseAmount;
  #endif
#endif
    gl_FragData[0] = vec4(f);
}
";

/// A second program that reads no option.
const FINAL: &str = "#version 120\nuniform sampler2D colortex0;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(colortex0, uv); }\n";
const FINAL_VERTEX: &str = "#version 120\nvarying vec2 uv;\nvoid main() { uv = gl_MultiTexCoord0.xy; gl_Position = ftransform(); }\n";

fn files() -> Vec<(&'static str, &'static str)> {
    vec![
        ("settings.glsl", SETTINGS),
        ("composite.vsh", VERTEX),
        ("composite.fsh", COMPOSITE),
        ("final.vsh", FINAL_VERTEX),
        ("final.fsh", FINAL),
    ]
}

fn validate(files: &[(&str, &str)], options: Options) -> Report {
    let pack = pack_from_memory("test/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    validate_pack(pack, &Options { threads: 2, ..options }).expect("the pack reads")
}

fn covering() -> Options {
    Options { profiles: Profiles::Covering(Coverage::Pairwise), ..Options::default() }
}

fn errors(report: &Report) -> Vec<String> {
    report.diagnostics.iter().filter(|d| d.is_error()).map(|d| d.to_string()).collect()
}

#[test]
fn the_covering_sets_find_mistakes_behind_toggles_pairs_and_nested_options() {
    let defaults = validate(&files(), Options::default());
    assert!(errors(&defaults).is_empty(), "{:?}", errors(&defaults));
    let report = validate(&files(), covering());
    let found = errors(&report);
    assert_eq!(found.len(), 3, "{found:#?}");
    let one = |needle: &str| found.iter().find(|e| e.contains(needle)).unwrap_or_else(|| panic!("no {needle}: {found:#?}")).clone();
    // Each error names its place and a command line that shows it.
    let godrays = one("undeclaredStrength");
    assert!(godrays.contains("composite.fsh:4") && godrays.contains("--set GODRAYS=on"), "{godrays}");
    let pair = one("composite.fsh:10");
    assert!(pair.contains("FOG_STYLE=2") && pair.contains("--set FOG=off"), "{pair}");
    let nested = one("noiseAmount");
    assert!(nested.contains("composite.fsh:14") && nested.contains("FOG_NOISE=on") && nested.contains("FOG_STYLE=3"), "{nested}");
    // Each is reduced to the options it needs, whatever else its sets held.
    assert!(godrays.contains("shown with: --set GODRAYS=on\n"), "{godrays}");
    assert!(pair.contains("shown with: --set FOG=off --set FOG_STYLE=2\n"), "{pair}");
    assert!(nested.contains("shown with: --set FOG_NOISE=on --set FOG_STYLE=3\n"), "{nested}");
}

#[test]
fn each_distinct_program_text_is_validated_once() {
    let report = validate(&files(), covering());
    // composite tests four options (2 × 2 × 3 × 2 combinations, more than are taken whole):
    // every pair of their values, in 7 sets; final reads none: its one text.
    assert_eq!(report.plan.considered, 7 + 1, "{:?}", report.plan);
    assert_eq!(report.plan.covered, Some(SetsCovered::Pairs));
    // FOG_NOISE changes nothing unless FOG_STYLE is 3: those texts repeat.
    assert!(report.plan.identical >= 2, "{:?}", report.plan);
    // naga sees each distinct fragment text of composite once, its one vertex text once, and
    // final's two stages once.
    let composite_texts = report.plan.considered - report.plan.identical - 1;
    assert_eq!(report.stages_validated, composite_texts + 1 + 2, "{:?}", report.plan);
    let again = validate(&files(), covering());
    assert_eq!(errors(&again), errors(&report), "the same pack gives the same report");
}

#[test]
fn a_cache_folder_gives_the_same_report_without_validating_again() {
    let dir = tempfile::tempdir().unwrap();
    let with_cache = || Options { cache: Some(dir.path().to_path_buf()), ..covering() };
    let first = validate(&files(), with_cache());
    assert!(first.stages_validated > 0);
    let second = validate(&files(), with_cache());
    assert_eq!(second.stages_validated, 0, "every pair came from the cache");
    assert_eq!(errors(&second), errors(&first));
    let messages = |r: &Report| r.diagnostics.iter().map(|d| d.to_string()).collect::<Vec<_>>();
    assert_eq!(messages(&second), messages(&first));
    // A change to one program validates that program again, and the other comes from the cache.
    let mut changed = files();
    let fixed_final = FINAL.replace("texture2D(colortex0, uv)", "texture2D(colortex0, uv) * 0.5");
    changed[4] = ("final.fsh", Box::leak(fixed_final.into_boxed_str()));
    let third = validate(&changed, with_cache());
    assert_eq!(third.stages_validated, 2, "only final is new (its two stages are lowered together)");
    assert_eq!(errors(&third), errors(&first));
    // A damaged entry is a miss, not an error.
    for entry in std::fs::read_dir(dir.path()).unwrap() {
        std::fs::write(entry.unwrap().path(), "{ not json").unwrap();
    }
    let fourth = validate(&files(), with_cache());
    assert_eq!(errors(&fourth), errors(&first));
    assert!(fourth.stages_validated > 0);
}

#[test]
fn shards_split_the_program_texts_and_together_find_everything() {
    let whole = validate(&files(), covering());
    let mut found: BTreeSet<String> = BTreeSet::new();
    let mut validated = 0;
    for index in 0..3 {
        let shard = validate(&files(), Options { shard: Some(Shard { index, count: 3 }), ..covering() });
        let distinct = shard.plan.considered - shard.plan.identical - shard.plan.other_shards;
        validated += distinct;
        // Notes name the sets each shard saw; the error itself is the same.
        found.extend(shard.diagnostics.iter().filter(|d| d.is_error()).map(|d| format!("{}: {}", d.location.as_ref().unwrap(), d.message)));
    }
    assert_eq!(validated, whole.plan.considered - whole.plan.identical, "each distinct text in exactly one shard");
    let expected: BTreeSet<String> =
        whole.diagnostics.iter().filter(|d| d.is_error()).map(|d| format!("{}: {}", d.location.as_ref().unwrap(), d.message)).collect();
    assert_eq!(found, expected);
    assert_eq!(Shard::parse("2/4"), Ok(Shard { index: 1, count: 4 }));
    for bad in ["0/4", "5/4", "2", "a/b", "1/0"] {
        assert!(Shard::parse(bad).unwrap_err().contains("K/N"), "{bad}");
    }
}

#[test]
fn exhaustive_coverage_tries_every_combination_of_tested_options() {
    let report = validate(&files(), Options { profiles: Profiles::Covering(Coverage::Exhaustive), ..covering() });
    assert_eq!(errors(&report).len(), 3, "{:#?}", errors(&report));
}

/// A stray comma in a value list (`[.0, .2 .5]`, as a released pack ships it) is a value a
/// player can pick: the covering sets try it, and the substituted comma is a syntax error.
#[test]
fn a_stray_comma_in_a_value_list_is_found_where_the_value_lands() {
    let fragment = "#version 120\n#define BLOOM_AMOUNT .5 // [.0, .2 .5]\nuniform sampler2D colortex0;\nvoid main() {\n    vec4 glow = texture2D(colortex0, vec2(0.5));\n    gl_FragData[0] = glow * BLOOM_AMOUNT;\n}\n";
    let files = [("composite.vsh", VERTEX), ("composite.fsh", fragment)];
    assert!(errors(&validate(&files, Options::default())).is_empty());
    let report = validate(&files, covering());
    let found = errors(&report);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert!(found[0].contains("composite.fsh:6") && found[0].contains("`,` with no expression after it"), "{}", found[0]);
    assert!(found[0].contains("shown with: --set BLOOM_AMOUNT=.0,"), "{}", found[0]);
}

/// Players pick only what the menu shows: with screens listed, an option on none of them
/// (a stage's own `#define FSH`, tested by the file it includes) keeps its default.
#[test]
fn options_on_no_screen_keep_their_defaults() {
    let mut files = files();
    files.push(("shaders.properties", "screen = FOG FOG_STYLE FOG_NOISE\n"));
    let report = validate(&files, covering());
    let found = errors(&report);
    assert!(!found.iter().any(|e| e.contains("undeclaredStrength")), "GODRAYS is on no screen: {found:#?}");
    assert_eq!(found.len(), 2, "{found:#?}");
    assert!(!report.option_sets.iter().any(|s| s.contains("GODRAYS")), "{:?}", report.option_sets);
}
