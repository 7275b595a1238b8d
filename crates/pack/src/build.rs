//! `build`: templates → shipped pack per dialect → validation of every option set → zips.
//! Nothing is written unless every dialect validates.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use tidepack_glsl::{Code, Diagnostic};
use tidepack_loader::option_lines::OptionSet;

use crate::{archive, properties};
use crate::dialect::Dialect;
use crate::pack_options::{self, PackOptions};
use crate::shipped::ShippedPack;
use crate::specialise::{Specialisation, specialise};
use crate::source::PackSource;
use crate::option_sets::{self, Coverage, Progress, ValidationReport};

#[derive(Clone, Debug)]
pub struct BuildOptions {
    /// The folder holding pack.toml and shaders/ (`shaderpack`).
    pub source_dir: PathBuf,
    pub out_dir: PathBuf,
    pub dialects: Vec<Dialect>,
    /// Profile whose values become the defaults in the shipped GLSL.
    pub profile: Option<String>,
    /// How many option combinations to validate.
    pub coverage: Coverage,
    /// Uniforms folded into constants for one scene (`build --scene`); the zip names the scene.
    pub specialisation: Option<Specialisation>,
}

#[derive(Clone, Debug)]
pub struct DialectOutcome {
    pub dialect: Dialect,
    pub validation: ValidationReport,
    pub zip: PathBuf,
    pub zip_bytes: u64,
}

#[derive(Clone, Debug)]
pub struct BuildReport {
    pub pack_name: String,
    pub version: String,
    pub profile: String,
    pub options: usize,
    pub outcomes: Vec<DialectOutcome>,
    /// Uniforms folded into constants, when specialised for a scene.
    pub folded: Vec<String>,
    /// Problems that do not stop the build (unchecked properties, options no program reads).
    pub warnings: Vec<Diagnostic>,
    pub elapsed: Duration,
}

/// Why a build failed, with the texts the diagnostics point into.
#[derive(Debug)]
pub struct BuildFailure {
    pub diagnostics: Vec<Diagnostic>,
    /// Zips renamed into place before a later one failed to (empty in every other failure).
    pub written: Vec<PathBuf>,
    /// The command line named what the pack does not have (a profile), or a folder that is no
    /// pack source: a usage error.
    pub usage: bool,
    sources: HashMap<String, String>,
}

impl BuildFailure {
    fn new(diagnostics: Vec<Diagnostic>) -> Self {
        BuildFailure { diagnostics, written: Vec::new(), usage: false, sources: HashMap::new() }
    }

    /// Text of a file a diagnostic names, for the snippet.
    pub fn source_of(&self, path: &str) -> Option<String> {
        self.sources.get(path).cloned().or_else(|| std::fs::read_to_string(path).ok())
    }
}

/// The zip path of a dialect: `<out>/<Name>-<version>-<dialect>.zip`, or
/// `<out>/<Name>-<version>-<dialect>-<variant>.zip` for a specialised pack.
pub fn zip_path(out_dir: &Path, name: &str, version: &str, dialect: Dialect, variant: Option<&str>) -> PathBuf {
    match variant {
        Some(variant) => out_dir.join(format!("{name}-{version}-{}-{variant}.zip", dialect.slug())),
        None => out_dir.join(format!("{name}-{version}-{}.zip", dialect.slug())),
    }
}

/// The validated pack of each dialect, and the warnings found on the way.
pub type Validated = (Vec<(ShippedPack, ValidationReport)>, Vec<Diagnostic>);

/// Generates and validates the pack in each dialect (see the crate docs), specialised first
/// when `specialisation` is given, so what is validated is what ships. The manifest's
/// shaders.properties entries are checked on the first pack generated, before any validation.
pub fn generate_validated(
    source: &PackSource,
    options: &PackOptions,
    dialects: &[Dialect],
    defaults: &OptionSet,
    coverage: Coverage,
    specialisation: Option<&Specialisation>,
    progress: Option<&ProgressReport<'_>>,
) -> Result<Validated, BuildFailure> {
    let profiles: Vec<OptionSet> = source
        .manifest
        .profiles
        .iter()
        .filter_map(|p| pack_options::profile_set(source, options, &p.name).ok())
        .collect();
    let mut packs = Vec::new();
    let mut diagnostics = Vec::new();
    let mut sources = HashMap::new();
    let mut warnings = Vec::new();
    // Validation enumerates values around what ships, which a profile may have changed.
    let shipped_options = pack_options::with_defaults(options, defaults);
    for &dialect in dialects {
        let mut pack = ShippedPack::generate(source, options, dialect, defaults).map_err(BuildFailure::new)?;
        if packs.is_empty() && diagnostics.is_empty() {
            let (errors, found) = properties::check(source, &pack);
            if !errors.is_empty() {
                return Err(BuildFailure::new(errors));
            }
            warnings.extend(found);
        }
        if let Some(spec) = specialisation {
            specialise(&mut pack, spec);
        }
        let report = progress.map(|p| move |step: Progress| p(dialect, step));
        let report = report.as_ref().map(|r| r as &(dyn Fn(Progress) + Sync));
        match option_sets::validate_pack(&pack, &shipped_options, coverage, &profiles, report) {
            Ok(report) => packs.push((pack, report)),
            Err(errors) => {
                for diag in errors {
                    let location = diag.location.as_ref().map(|l| pack.to_template(l, source));
                    if let Some(loc) = &location
                        && let Some(text) = pack.diagnostic_source(&loc.path, source)
                    {
                        sources.insert(loc.path.clone(), text);
                    }
                    let note = format!("in the {dialect} dialect");
                    diagnostics.push(Diagnostic { location, ..diag }.with_note(note));
                }
            }
        }
    }
    if diagnostics.is_empty() { Ok((packs, warnings)) } else { Err(BuildFailure { diagnostics, written: Vec::new(), usage: false, sources }) }
}

/// Hears how far each dialect's validation is.
pub type ProgressReport<'a> = dyn Fn(Dialect, Progress) + Sync + 'a;

/// Builds the pack (see the module docs); `progress` hears how far each dialect's validation is.
pub fn build(opts: &BuildOptions, progress: Option<&ProgressReport<'_>>) -> Result<BuildReport, BuildFailure> {
    let started = Instant::now();
    // No pack source at all is the command line's mistake (--source); a broken one is the pack's.
    let source =
        PackSource::load(&opts.source_dir).map_err(|d| BuildFailure { usage: d.code == Code::Usage, ..BuildFailure::new(vec![d]) })?;
    let options = pack_options::collect(&source).map_err(BuildFailure::new)?;
    let problems = pack_options::check_manifest(&source, &options);
    if !problems.is_empty() {
        return Err(BuildFailure::new(problems));
    }
    let profile = opts.profile.clone().unwrap_or_else(|| source.manifest.pack.default_profile.clone());
    let defaults =
        pack_options::profile_set(&source, &options, &profile).map_err(|d| BuildFailure { usage: true, ..BuildFailure::new(vec![d]) })?;
    let spec = opts.specialisation.as_ref();
    let (packs, mut warnings) = generate_validated(&source, &options, &opts.dialects, &defaults, opts.coverage, spec, progress)?;
    for option in options.values() {
        if !packs.iter().any(|(_, report)| report.options_read.contains(&option.name)) {
            warnings.push(
                Diagnostic::warning(
                    Code::UnusedOption,
                    format!("option {} changes no program: no shader's text depends on it", option.name),
                    Some(option.declared_at.clone()),
                )
                .with_note("players can set it in the menu to no effect; use it in a program or remove it"),
            );
        }
    }
    let folded = packs.first().map(|(pack, _)| pack.folded_uniforms.clone()).unwrap_or_default();
    let variant = spec.map(|s| s.variant_name());
    let info = &source.manifest.pack;
    let zips: Vec<archive::ZipContents> = packs
        .iter()
        .map(|(pack, _)| {
            let texts = pack.files.iter().map(|(path, file)| (format!("shaders/{path}"), file.text.as_bytes()));
            let binaries = pack.binaries.iter().map(|(path, bytes)| (format!("shaders/{path}"), &bytes[..]));
            let zip = zip_path(&opts.out_dir, &info.name, &info.version, pack.dialect, variant.as_deref());
            (zip, texts.chain(binaries).collect())
        })
        .collect();
    let sizes = archive::write_zips(&zips).map_err(|f| BuildFailure {
        written: f.written,
        ..BuildFailure::new(vec![Diagnostic::error(Code::Template, f.message, None)])
    })?;
    let paths: Vec<PathBuf> = zips.into_iter().map(|(zip, _)| zip).collect();
    let outcomes = packs
        .into_iter()
        .zip(paths)
        .zip(sizes)
        .map(|(((pack, validation), zip), zip_bytes)| DialectOutcome { dialect: pack.dialect, validation, zip, zip_bytes })
        .collect();
    Ok(BuildReport {
        pack_name: info.name.clone(),
        version: info.version.clone(),
        profile,
        options: options.len(),
        outcomes,
        folded,
        warnings,
        elapsed: started.elapsed(),
    })
}
