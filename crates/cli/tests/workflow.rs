//! docs/github-actions-validate.yml is a workflow a pack author copies as it is, so it is
//! tested as it is: parsed, checked for what it promises (a validator cached whatever the
//! pack's verdict, a validate-only build, a shard matrix as wide as SHARDS, a job summary,
//! blessing by hand), and its `run:` steps run by bash in a pack repository of our own, with
//! the `tidepack` under test on PATH and this checkout as the tidepack repository. Only the
//! steps that install something (apt-get, rustup, cargo install) or push are not run.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use yaml_rust2::{Yaml, YamlLoader};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

fn workflow() -> Yaml {
    let text = std::fs::read_to_string(repo_root().join("docs/github-actions-validate.yml")).unwrap();
    YamlLoader::load_from_str(&text).expect("the workflow is valid YAML").remove(0)
}

/// The steps that install or publish, which a test machine does not run: each must exist, so
/// that a renamed step is noticed, and each may only call these programs.
const NOT_RUN: &[(&str, &[&str])] = &[
    ("Build the validator", &["rustup", "cargo install"]),
    ("Install Mesa's OpenGL driver (for --driver)", &["sudo apt-get"]),
    ("Install Mesa's CPU Vulkan and OpenGL drivers", &["sudo apt-get"]),
    ("Build the renderer", &["rustup", "cargo install"]),
    ("Commit the blessed screens", &["git"]),
];

fn steps<'a>(workflow: &'a Yaml, job: &str) -> &'a [Yaml] {
    workflow["jobs"][job]["steps"].as_vec().unwrap_or_else(|| panic!("job {job} has steps"))
}

fn string<'a>(yaml: &'a Yaml, what: &str) -> &'a str {
    yaml.as_str().unwrap_or_else(|| panic!("{what} is a string: {yaml:?}"))
}

/// What a run of the workflow knows: the values of the expressions its steps use.
struct Run {
    repository: tempfile::TempDir,
    bin: tempfile::TempDir,
    values: BTreeMap<&'static str, String>,
    output: PathBuf,
    summary: PathBuf,
}

impl Run {
    /// A pack repository holding `pack` (a folder with `shaders/`) at its root.
    fn new(pack: &Path) -> Run {
        let repository = tempfile::tempdir().unwrap();
        copy_folder(pack, repository.path());
        let bin = tempfile::tempdir().unwrap();
        std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_tidepack"), bin.path().join("tidepack")).unwrap();
        let output = bin.path().join("github_output");
        let summary = bin.path().join("step_summary.md");
        let values = BTreeMap::from([
            ("vars.TIDEPACK_REPO", repo_root().display().to_string()),
            ("vars.TIDEPACK_REF || 'main'", "HEAD".to_string()),
            ("runner.os", "Linux".to_string()),
            ("github.sha", "0123456789abcdef".to_string()),
            ("inputs.bless && 'yes' || ''", String::new()),
        ]);
        Run { repository, bin, values, output, summary }
    }

    /// `text` with every `${{ … }}` replaced by its value; an expression the test does not
    /// know fails it, so a new one in the workflow is given a value here.
    fn expand(&self, text: &str) -> String {
        let mut out = String::new();
        let mut rest = text;
        while let Some(start) = rest.find("${{") {
            out.push_str(&rest[..start]);
            let end = rest[start..].find("}}").expect("a closed expression") + start;
            let expression = rest[start + 3..end].trim();
            let value = self.values.get(expression).unwrap_or_else(|| panic!("the test gives no value to `{expression}`"));
            out.push_str(value);
            rest = &rest[end + 2..];
        }
        out.push_str(rest);
        out
    }

    /// Runs step `name` of `job` as GitHub runs a `run:` step (`bash -e`), with the workflow's
    /// and the step's environment; returns its exit code and output.
    fn step(&self, workflow: &Yaml, job: &str, name: &str) -> (i32, String) {
        let step = steps(workflow, job)
            .iter()
            .find(|s| s["name"].as_str().is_some_and(|n| self.expand(n) == name))
            .unwrap_or_else(|| panic!("job {job} has no step `{name}`"));
        let script = self.expand(string(&step["run"], name));
        let mut command = Command::new("bash");
        command.args(["-e", "-c", &script]).current_dir(self.repository.path());
        let path = format!("{}:{}", self.bin.path().display(), std::env::var("PATH").unwrap_or_default());
        command.env("PATH", path).env("GITHUB_OUTPUT", &self.output).env("GITHUB_STEP_SUMMARY", &self.summary);
        for env in [&workflow["env"], &step["env"]] {
            for (key, value) in env.as_hash().into_iter().flatten() {
                let value = match value {
                    Yaml::Integer(n) => n.to_string(),
                    other => self.expand(string(other, "an env value")),
                };
                command.env(string(key, "an env name"), value);
            }
        }
        let result = command.output().expect("run bash");
        let said = format!("{}{}", String::from_utf8_lossy(&result.stdout), String::from_utf8_lossy(&result.stderr));
        (result.status.code().unwrap_or(-1), said)
    }

    /// The `name=value` lines steps wrote to $GITHUB_OUTPUT.
    fn outputs(&self) -> BTreeMap<String, String> {
        let text = std::fs::read_to_string(&self.output).unwrap_or_default();
        text.lines().filter_map(|l| l.split_once('=')).map(|(k, v)| (k.to_string(), v.to_string())).collect()
    }
}

fn copy_folder(from: &Path, to: &Path) {
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            std::fs::create_dir_all(&target).unwrap();
            copy_folder(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

#[test]
fn the_workflow_promises_what_the_issue_asks() {
    let workflow = workflow();
    let on = &workflow["on"];
    assert!(!on["push"].is_badvalue() && !on["pull_request"].is_badvalue(), "runs on pushes and pull requests");
    assert_eq!(on["workflow_dispatch"]["inputs"]["bless"]["type"].as_str(), Some("boolean"), "blessing is a manual run");
    let jobs: Vec<&str> = workflow["jobs"].as_hash().unwrap().keys().map(|k| string(k, "a job name")).collect();
    assert_eq!(jobs, ["tool", "validate", "covering", "render"]);

    // The validator is built and saved by a job that never looks at the pack, so a pack that
    // keeps failing does not rebuild it; it is built without the renderer.
    let tool = steps(&workflow, "tool");
    assert!(!tool.iter().any(|s| s["uses"].as_str().is_some_and(|u| u.starts_with("actions/checkout"))), "the tool job reads no pack");
    let build = tool.iter().find(|s| s["name"].as_str() == Some("Build the validator")).unwrap();
    assert!(string(&build["run"], "build").contains("cargo install --locked --no-default-features"), "a validate-only build");
    assert!(tool.iter().any(|s| s["uses"].as_str() == Some("actions/cache/save@v4")), "the tool job saves the validator");
    for job in ["validate", "covering"] {
        assert_eq!(workflow["jobs"][job]["needs"].as_str(), Some("tool"));
        let restore = steps(&workflow, job).iter().find(|s| s["name"].as_str() == Some("Restore the validator")).unwrap();
        assert_eq!(restore["with"]["fail-on-cache-miss"].as_bool(), Some(true), "{job} uses the tool job's build");
    }

    // One matrix job per shard.
    let shards = workflow["env"]["SHARDS"].as_i64().unwrap();
    let matrix = workflow["jobs"]["covering"]["strategy"]["matrix"]["shard"].as_vec().unwrap();
    assert_eq!(matrix.iter().map(|s| s.as_i64().unwrap()).collect::<Vec<_>>(), (1..=shards).collect::<Vec<_>>());

    // Every action is pinned to a major version, and the steps it does not run only install.
    for job in &jobs {
        for step in steps(&workflow, job) {
            if let Some(uses) = step["uses"].as_str() {
                assert!(uses.rsplit_once('@').is_some_and(|(_, v)| v.starts_with('v')), "{uses} is pinned");
            }
        }
    }
    for (name, programs) in NOT_RUN {
        let step = jobs.iter().flat_map(|j| steps(&workflow, j)).find(|s| s["name"].as_str() == Some(name)).unwrap_or_else(|| panic!("no step `{name}`"));
        for line in string(&step["run"], name).lines().map(str::trim).filter(|l| !l.is_empty()) {
            assert!(programs.iter().any(|p| line.starts_with(p)), "`{name}` runs `{line}`, which the test would have to run");
        }
    }
}

#[test]
fn the_workflow_steps_run_on_a_pack_repository() {
    let workflow = workflow();
    let mut run = Run::new(&repo_root().join("tests/packs/flip_chain"));

    // The tool job: a missing TIDEPACK_REPO is said, and the commit is found.
    let mut unset = Run::new(&repo_root().join("tests/packs/flip_chain"));
    unset.values.insert("vars.TIDEPACK_REPO", String::new());
    let (code, said) = unset.step(&workflow, "tool", "Find the tidepack commit");
    assert_eq!(code, 1, "{said}");
    assert!(said.contains("::error") && said.contains("TIDEPACK_REPO"), "{said}");
    let (code, said) = run.step(&workflow, "tool", "Find the tidepack commit");
    assert_eq!(code, 0, "{said}");
    let commit = run.outputs().get("commit").cloned().unwrap_or_default();
    assert!(commit.len() == 40 && commit.bytes().all(|b| b.is_ascii_hexdigit()), "commit={commit}: {said}");
    run.values.insert("steps.tidepack.outputs.commit", commit.clone());
    run.values.insert("needs.tool.outputs.commit", commit);

    // validate: annotations, and the job summary.
    let (code, said) = run.step(&workflow, "validate", "Validate the defaults and every profile");
    assert_eq!(code, 0, "{said}");
    let summary = std::fs::read_to_string(&run.summary).unwrap();
    assert!(summary.contains("### tidepack validate") && summary.contains(": passes"), "{summary}");

    // covering: every shard, with the findings cache kept between runs.
    let shards = workflow["env"]["SHARDS"].as_i64().unwrap();
    for shard in 1..=shards {
        run.values.insert("matrix.shard", shard.to_string());
        let (code, said) = run.step(&workflow, "covering", &format!("Validate shard {shard}"));
        assert_eq!(code, 0, "shard {shard}: {said}");
    }
    assert!(run.repository.path().join(".tidepack-cache").is_dir(), "the findings cache is written where the cache step saves it");

    // render: no blessed screens yet is a warning; a blessing run writes them; then they are compared.
    let (code, said) = run.step(&workflow, "render", "Render");
    assert_eq!(code, 0, "{said}");
    assert!(said.contains("::warning") && said.contains("no blessed screens"), "{said}");
    assert!(run.repository.path().join("render/case4_above_near.png").is_file(), "the pictures the artifact uploads");
    run.values.insert("inputs.bless && 'yes' || ''", "yes".into());
    let (code, said) = run.step(&workflow, "render", "Render");
    assert_eq!(code, 0, "{said}");
    assert!(run.repository.path().join(".tidepack/blessed/glass_over_land.png").is_file(), "{said}");
    run.values.insert("inputs.bless && 'yes' || ''", String::new());
    let (code, said) = run.step(&workflow, "render", "Render");
    assert_eq!(code, 0, "{said}");
    assert_eq!(said.matches("mean FLIP 0.00000").count(), 3, "{said}");

    // A mistake in the pack fails the validate step, annotated at its line.
    let fragment = run.repository.path().join("shaders/composite.fsh");
    let text = std::fs::read_to_string(&fragment).unwrap();
    let broken = text.replacen("void main()", "float broken() { return undefined_name; }\nvoid main()", 1);
    assert_ne!(broken, text);
    std::fs::write(&fragment, broken).unwrap();
    let (code, said) = run.step(&workflow, "validate", "Validate the defaults and every profile");
    assert_eq!(code, 1, "{said}");
    assert!(said.lines().any(|l| l.starts_with("::error ") && l.contains("file=shaders/composite.fsh")), "{said}");
}
