//! Prints the shipped and lowered text of one stage of the pack (a debugging aid):
//! `cargo run -p tidepack-pack --example dump_lowered -- composite.fsh 120`
use std::sync::Arc;
use tidepack_glsl::{naga_check, preprocess, Stage};
use tidepack_loader::macros::StandardMacros;
use tidepack_pack::{dialect::Dialect, pack_options, shipped::ShippedPack, source::PackSource};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (path, dialect) = (&args[1], if args.get(2).map(String::as_str) == Some("330") { Dialect::Glsl330 } else { Dialect::Glsl120 });
    let source = PackSource::load("shaderpack".as_ref()).unwrap();
    let options = pack_options::collect(&source).unwrap();
    let pack = ShippedPack::generate(&source, &options, dialect, &Default::default()).unwrap();
    let program = pack.programs().into_iter().find(|p| p.stages.iter().any(|(_, p)| p == path)).unwrap();
    let macros = StandardMacros::default().preprocess_options();
    let stages: Vec<(Stage, Arc<preprocess::Preprocessed>)> = program.stages.iter().map(|(s, p)| {
        let provider: std::collections::HashMap<String, Arc<str>> = pack.files.iter().map(|(k, v)| (k.clone(), v.text.clone())).collect();
        (*s, Arc::new(preprocess::preprocess(&provider, p, &macros).unwrap()))
    }).collect();
    let lowered = naga_check::lower_program(&stages).unwrap();
    for (l, (_, p)) in lowered.iter().zip(&program.stages) {
        if p == path { println!("{}", l.lowered.text); }
    }
}
