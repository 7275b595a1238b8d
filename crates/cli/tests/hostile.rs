//! Hostile inputs of a few MB, each run as a player or a CI job would run it, under the
//! promise that none takes more than 600 MiB of resident memory or more than a minute, that
//! each ends with a clear error or a verdict (never a panic or a signal), and with the exit
//! code the docs give. The peak resident memory of each run is read from the kernel
//! (`wait4`'s `ru_maxrss`).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The validator's promise for an input of a few MB.
const MAX_RESIDENT_BYTES: u64 = 600 << 20;
/// Past this a run is killed and reported as a hang.
const HANG: Duration = Duration::from_secs(120);

struct Run {
    code: Option<i32>,
    signal: Option<i32>,
    peak_bytes: u64,
    took: Duration,
    stderr: String,
}

/// Runs `tidepack ARGS` to the end, with the peak resident memory the kernel counted for it.
fn run(args: &[&str]) -> Run {
    let stderr = tempfile::NamedTempFile::new().unwrap();
    let started = Instant::now();
    let child = Command::new(env!("CARGO_BIN_EXE_tidepack"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.."))
        .stdout(Stdio::null())
        .stderr(stderr.reopen().unwrap())
        .spawn()
        .expect("run tidepack");
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: rusage is plain data the kernel fills; `pid` is our own child, reaped only here.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    loop {
        let reaped = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if reaped == pid {
            break;
        }
        assert!(reaped == 0, "wait4 failed");
        if started.elapsed() > HANG {
            unsafe { libc::kill(pid, libc::SIGKILL) };
            panic!("tidepack {args:?} still ran after {HANG:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let exited = libc::WIFEXITED(status);
    Run {
        code: exited.then(|| libc::WEXITSTATUS(status)),
        signal: libc::WIFSIGNALED(status).then(|| libc::WTERMSIG(status)),
        // Linux counts ru_maxrss in KiB.
        peak_bytes: usage.ru_maxrss as u64 * 1024,
        took: started.elapsed(),
        stderr: std::fs::read_to_string(stderr.path()).unwrap_or_default(),
    }
}

fn zip_of(path: &Path, entries: &[(&str, Vec<u8>)]) {
    let mut zip = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    for (name, data) in entries {
        zip.start_file(*name, zip::write::SimpleFileOptions::default()).unwrap();
        zip.write_all(data).unwrap();
    }
    zip.finish().unwrap();
}

const VSH: &str = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";

fn program(body: &str) -> Vec<u8> {
    format!("#version 120\n{body}\nvoid main() {{ gl_FragColor = vec4(1.0); }}\n").into_bytes()
}

/// The workspace's pseudo-random bytes are not needed here: a fixed linear congruence gives
/// bytes that deflate cannot shrink, so the zip stays a few MB.
fn incompressible(len: usize, seed: u64) -> Vec<u8> {
    let mut x = seed;
    (0..len)
        .map(|_| {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 56) as u8
        })
        .collect()
}

/// A PNG that is only its signature, a header claiming `width` x `height` and no pixels:
/// what a 400 KB file of a huge, flat image looks like to a reader of its size.
fn png_header_only(width: u32, height: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
            }
        }
        !crc
    }
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = |kind: &[u8], data: &[u8]| {
        png.extend((data.len() as u32).to_be_bytes());
        let body = [kind, data].concat();
        png.extend(&body);
        png.extend(crc32(&body).to_be_bytes());
    };
    // 8-bit greyscale, deflate, no filter, no interlace; then an empty image stream.
    chunk(b"IHDR", &[width.to_be_bytes(), height.to_be_bytes()].concat().into_iter().chain([8, 0, 0, 0, 0]).collect::<Vec<u8>>());
    chunk(b"IDAT", &[]);
    chunk(b"IEND", &[]);
    png
}

struct Case {
    name: &'static str,
    args: Vec<String>,
    /// The exit code the docs give for it.
    code: i32,
    /// What stderr says.
    says: &'static str,
}

fn cases(dir: &Path) -> Vec<Case> {
    let at = |name: &str| dir.join(name);
    let shown = |p: PathBuf| p.display().to_string();
    let mut cases = Vec::new();
    let mut validate = |name: &'static str, entries: Vec<(&str, Vec<u8>)>, code: i32, says: &'static str| {
        let path = at(&format!("{name}.zip"));
        zip_of(&path, &entries);
        cases.push(Case { name, args: vec!["validate".into(), shown(path)], code, says });
    };
    let globals: String = (0..5_000).map(|i| format!("float g{i} = 1.0;\nfloat h{i} = g{i} * 2.0;\n")).collect();
    validate("global_initializers", vec![("shaders/composite.vsh", VSH.into()), ("shaders/composite.fsh", program(&globals))], 0, "");
    let functions: String = (0..2_500).map(|i| format!("float g{i};\nfloat f{i}() {{ return g{i}; }}\n")).collect();
    validate("functions_times_globals", vec![("shaders/composite.vsh", VSH.into()), ("shaders/composite.fsh", program(&functions))], 0, "the 2000000 naga is given");
    let mut bad_text = Vec::new();
    let mut includes = String::new();
    for i in 0..7 {
        let bytes: Vec<u8> = incompressible(1 << 20, i).into_iter().map(|b| b | 0x80).collect();
        bad_text.push((format!("shaders/lib/b{i}.glsl"), [b"//".as_slice(), &bytes, b"\n"].concat()));
        includes.push_str(&format!("#include \"/lib/b{i}.glsl\"\n"));
    }
    let stages: Vec<(String, Vec<u8>)> = ["composite", "composite1", "deferred", "final"]
        .iter()
        .flat_map(|p| [(format!("shaders/{p}.fsh"), program(&includes)), (format!("shaders/{p}.vsh"), VSH.into())])
        .collect();
    let entries = bad_text.iter().chain(&stages).map(|(n, b)| (n.as_str(), b.clone())).collect();
    validate("not_utf8", entries, 0, "not valid UTF-8");
    let long_line: Vec<u8> = [b"float x = 1.0".as_slice(), &incompressible(4 << 20, 7).iter().map(|b| b'a' + b % 26).collect::<Vec<u8>>(), b";\n"].concat();
    validate(
        "one_line_include",
        vec![("shaders/composite.vsh", VSH.into()), ("shaders/composite.fsh", program("#include \"/lib/long.glsl\"")), ("shaders/lib/long.glsl", long_line)],
        1,
        "bytes long: the snippet shows",
    );
    let chain: String = (0..20_000).map(|i| format!("profile.P{i}=profile.P{}\n", i + 1)).collect::<String>() + "profile.P20000=\n";
    validate("profile_chain", vec![("shaders/composite.vsh", VSH.into()), ("shaders/composite.fsh", program("")), ("shaders/shaders.properties", chain.into_bytes())], 0, "");
    let lattice: String = (0..40)
        .map(|l| format!("profile.A{l}=profile.A{n} profile.B{n}\nprofile.B{l}=profile.A{n} profile.B{n}\n", n = l + 1))
        .collect::<String>()
        + "profile.A40=\nprofile.B40=\n";
    validate("profile_lattice", vec![("shaders/composite.vsh", VSH.into()), ("shaders/composite.fsh", program("")), ("shaders/shaders.properties", lattice.into_bytes())], 0, "");
    let nested = "(".repeat(200_000) + "1.0" + &")".repeat(200_000);
    validate("deep_parentheses", vec![("shaders/composite.vsh", VSH.into()), ("shaders/composite.fsh", program(&format!("float x = {nested};")))], 1, "");
    let mut all_profiles = |name: &'static str, zip: &str, code: i32, says: &'static str| {
        cases.push(Case { name, args: vec!["validate".into(), shown(at(zip)), "--all-profiles".into()], code, says });
    };
    all_profiles("profile_chain_all", "profile_chain.zip", 1, "budget for profiles");
    all_profiles("profile_lattice_all", "profile_lattice.zip", 0, "");
    let pipe = at("pipe.zip");
    let made = Command::new("mkfifo").arg(&pipe).status().expect("mkfifo");
    assert!(made.success());
    cases.push(Case { name: "named_pipe", args: vec!["validate".into(), shown(pipe)], code: 2, says: "neither a folder nor a regular file" });
    let scene = |name: &'static str, from: &str, to: &str, says: &'static str| {
        let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/case4_above_near.toml")).unwrap();
        assert!(text.contains(from), "{from}");
        let path = at(&format!("{name}.toml"));
        std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
        Case { name, args: vec!["render".into(), shown(path), "--out".into(), shown(at("out"))], code: 2, says }
    };
    let pack = at("texture_pack/shaders");
    std::fs::create_dir_all(&pack).unwrap();
    std::fs::write(pack.join("composite.vsh"), "#version 120\nvarying vec2 uv;\nvoid main() { gl_Position = ftransform(); uv = gl_MultiTexCoord0.xy; }\n").unwrap();
    std::fs::write(pack.join("composite.fsh"), "#version 120\nuniform sampler2D colortex7;\nvarying vec2 uv;\nvoid main() { gl_FragColor = texture2D(colortex7, uv); }\n").unwrap();
    std::fs::write(pack.join("shaders.properties"), "texture.composite.colortex7=big.png\n").unwrap();
    std::fs::write(pack.join("big.png"), png_header_only(20_000, 20_000)).unwrap();
    let scene_file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/case4_above_near.toml");
    cases.push(Case {
        name: "texture_20000_square",
        args: vec!["render".into(), "--pack".into(), shown(at("texture_pack")), shown(scene_file), "--out".into(), shown(at("out"))],
        code: 1,
        says: "more than the budget of 16777216",
    });
    cases.push(scene("water_a_million_blocks_wide", "min = [-32.0, -32.0]\nmax = [32.0, 22.0]", "min = [-1e6, -1e6]\nmax = [1e6, 1e6]", "budget of 200000"));
    cases.push(scene("camera_at_1e308", "position = [0.0, 67.0, -2.0]", "position = [1e308, 67.0, -2.0]", "world border"));
    cases.push(scene("resolution_4096", "resolution = [640, 360]", "resolution = [4096, 4096]", "budget of 384 MiB"));
    cases
}

#[test]
fn hostile_inputs_stay_within_memory_and_time_and_end_as_the_docs_say() {
    let dir = tempfile::tempdir().unwrap();
    let mut problems = Vec::new();
    for case in cases(dir.path()) {
        let args: Vec<&str> = case.args.iter().map(String::as_str).collect();
        let run = run(&args);
        eprintln!("{}: exit {:?}, {} MiB peak, {:.2} s", case.name, run.code, run.peak_bytes >> 20, run.took.as_secs_f64());
        if run.signal.is_some() || run.stderr.contains("panicked") {
            problems.push(format!("{}: crashed (signal {:?}): {}", case.name, run.signal, run.stderr));
        } else if run.code != Some(case.code) {
            problems.push(format!("{}: exit {:?}, the docs say {}: {}", case.name, run.code, case.code, tail(&run.stderr)));
        } else if !run.stderr.contains(case.says) {
            problems.push(format!("{}: stderr does not say {:?}: {}", case.name, case.says, tail(&run.stderr)));
        }
        if run.peak_bytes > MAX_RESIDENT_BYTES {
            problems.push(format!("{}: {} MiB resident at its peak, over {} MiB", case.name, run.peak_bytes >> 20, MAX_RESIDENT_BYTES >> 20));
        }
        if run.stderr.len() > 64 << 10 {
            problems.push(format!("{}: printed {} bytes of diagnostics", case.name, run.stderr.len()));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

fn tail(text: &str) -> String {
    let start = text.len().saturating_sub(600);
    let start = (start..text.len()).find(|&i| text.is_char_boundary(i)).unwrap_or(text.len());
    text[start..].to_string()
}
