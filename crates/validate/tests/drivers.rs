//! Which drivers refuse what `validate` reports, and `--target`: errors name the driver
//! families that refuse them, an error no target refuses is a warning saying who does, and
//! macOS's OpenGL 4.1 limits are checked when macOS is a target. Minimal packs of our own.

use tidepack_glsl::Drivers;
use tidepack_loader::input::pack_from_memory;
use tidepack_validate::{Options, Report, validate_pack};

const VERTEX_120: &str = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";

fn validate(files: &[(&str, &str)], target: Drivers) -> Report {
    let pack = pack_from_memory("test/shaders/", files.iter().map(|(p, t)| (p.to_string(), t.as_bytes().to_vec())));
    validate_pack(pack, &Options { threads: 2, target, ..Options::default() }).expect("the pack reads")
}

fn errors(report: &Report) -> Vec<&tidepack_glsl::Diagnostic> {
    report.diagnostics.iter().filter(|d| d.is_error()).collect()
}

/// The `refused_by` list of the JSON diagnostic whose message contains `needle`.
fn refused_in_json(report: &Report, needle: &str) -> Vec<String> {
    let json: serde_json::Value = serde_json::from_str(&tidepack_validate::output::json(report)).unwrap();
    let diagnostic = json["diagnostics"].as_array().unwrap().iter().find(|d| d["message"].as_str().unwrap().contains(needle)).unwrap();
    diagnostic["refused_by"].as_array().unwrap().iter().map(|v| v.as_str().unwrap().to_string()).collect()
}

#[test]
fn a_reserved_word_is_refused_by_all_but_nvidia_and_a_typo_by_every_driver() {
    let fragment = "#version 120\nvoid main() {\n    float output = 1.0;\n    gl_FragColor = vec4(output, colr, 0.0, 1.0);\n}\n";
    let files = [("final.vsh", VERTEX_120), ("final.fsh", fragment)];
    let report = validate(&files, tidepack_validate::DEFAULT_TARGET);
    let found = errors(&report);
    let reserved = found.iter().find(|d| d.message.contains("output")).unwrap_or_else(|| panic!("{found:#?}"));
    assert_eq!(reserved.refused_by, Drivers::ALL_BUT_NVIDIA);
    assert!(reserved.notes.iter().any(|n| n == "refused by Mesa, AMD, Intel, macOS; NVIDIA accepts it"), "{:?}", reserved.notes);
    // Under NVIDIA alone, the same line is a warning that says who refuses it.
    let nvidia = validate(&files, Drivers::NVIDIA);
    let demoted = nvidia.diagnostics.iter().find(|d| d.message.contains("`output`")).expect("still reported");
    assert!(!demoted.is_error());
    assert!(demoted.notes.iter().any(|n| n.contains("only Mesa, AMD, Intel, macOS refuse this")), "{:?}", demoted.notes);
    assert_eq!(refused_in_json(&report, "`output`"), ["mesa", "amd", "intel", "macos"]);
    // A typo no compiler takes: every driver, in JSON too.
    let typo = validate(&[("final.vsh", VERTEX_120), ("final.fsh", "#version 120\nvoid main() { gl_FragColor = vec4(colr); }\n")], Drivers::NVIDIA);
    let found = errors(&typo);
    assert_eq!(found.len(), 1, "{found:#?}");
    assert_eq!(found[0].refused_by, Drivers::ALL);
    assert_eq!(refused_in_json(&typo, "colr"), ["mesa", "amd", "intel", "nvidia", "macos"]);
}

#[test]
fn macos_limits_count_when_macos_is_a_target() {
    let vertex_430 = "#version 430 compatibility\nvoid main() { gl_Position = ftransform(); }\n";
    let storage_410 = "#version 410 compatibility\nbuffer Histogram { float bins[]; };\nvoid main() { gl_FragData[0] = vec4(bins[0]); }\n";
    let compute = "#version 430\nlayout(local_size_x = 8) in;\nvoid main() {}\n";
    let files = [
        ("composite.vsh", vertex_430),
        ("composite.fsh", "#version 430 compatibility\nvoid main() { gl_FragData[0] = vec4(1.0); }\n"),
        ("composite1.vsh", "#version 410 compatibility\nvoid main() { gl_Position = ftransform(); }\n"),
        ("composite1.fsh", storage_410),
        ("composite2.csh", compute),
        ("composite2.vsh", VERTEX_120),
        ("composite2.fsh", "#version 120\nvoid main() { gl_FragData[0] = vec4(1.0); }\n"),
    ];
    let default = validate(&files, tidepack_validate::DEFAULT_TARGET);
    assert!(errors(&default).is_empty(), "macOS is no default target: {:#?}", errors(&default));
    let mac = validate(&files, Drivers::MACOS);
    let found: Vec<String> = errors(&mac).iter().map(|d| d.to_string()).collect();
    assert!(found.iter().any(|e| e.contains("composite.vsh:1") && e.contains("`#version 430` is above 410")), "{found:#?}");
    assert!(found.iter().any(|e| e.contains("composite1.fsh:2") && e.contains("shader storage blocks")), "{found:#?}");
    assert!(found.iter().any(|e| e.contains("composite2.csh:1") && e.contains("compute shaders need OpenGL 4.3")), "{found:#?}");
    assert!(errors(&mac).iter().all(|d| d.refused_by == Drivers::MACOS));
}

#[test]
fn target_lists_are_read_by_name() {
    assert_eq!(Drivers::parse("mesa,amd"), Ok(Drivers::MESA.union(Drivers::AMD)));
    assert_eq!(Drivers::parse("all"), Ok(Drivers::ALL));
    assert!(Drivers::parse("mesa,voodoo").unwrap_err().contains("unknown driver `voodoo`"));
    assert!(Drivers::parse("").is_err());
}
