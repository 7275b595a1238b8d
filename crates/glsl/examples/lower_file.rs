//! Prints the lowered form of a shader file and naga's verdict (a debugging aid).
use std::collections::HashMap;
use std::sync::Arc;
use tidepack_glsl::{naga_check, preprocess, Stage};

fn main() {
    let path = std::env::args().nth(1).expect("usage: lower_file FILE");
    let text = std::fs::read_to_string(&path).unwrap();
    let files: HashMap<String, Arc<str>> = [(path.clone(), Arc::from(text))].into();
    let stage = Stage::from_path(&path).expect(".vsh or .fsh");
    let pre = Arc::new(preprocess::preprocess(&files, &path, &Default::default()).unwrap());
    let mut lowered = naga_check::lower_program(&[(stage, pre)]).unwrap();
    // Already Vulkan GLSL: hand it to naga as it is.
    if text_is_450(&path) {
        lowered[0].lowered.text = std::fs::read_to_string(&path).unwrap();
    }
    println!("{}", lowered[0].lowered.text);
    let mut fe = Default::default();
    match naga_check::validate_stage(&mut fe, &lowered[0], &files) {
        Ok(_) => println!("-- naga: ok"),
        Err(d) => d.iter().for_each(|d| println!("-- {d}")),
    }
}

fn text_is_450(path: &str) -> bool {
    std::fs::read_to_string(path).is_ok_and(|t| t.starts_with("#version 450"))
}
