//! Reading a pack (folder or zip) into memory, hostile input included.
//!
//! Nothing is ever written: zip entries are read into memory, so entry names with `..` or an
//! absolute path can do no harm; they are reported and skipped like the other suspicious
//! entries (zip bombs by size or compression ratio, symbolic links, unreadable entries).

use std::collections::BTreeMap;
use std::io::{Read, Seek};
use std::path::Path;
use std::sync::Arc;

use tidepack_glsl::{Code, Diagnostic, Location};

use crate::loader::Loader;
use crate::option_space::Dimension;

/// Limits on what is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Largest single file, uncompressed.
    pub max_file_bytes: u64,
    /// Largest sum of all files read.
    pub max_total_bytes: u64,
    /// Largest compression ratio of an entry bigger than [`Limits::ratio_floor_bytes`].
    pub max_ratio: u64,
    pub ratio_floor_bytes: u64,
    /// Most entries (files and folders) a pack may have.
    pub max_entries: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_file_bytes: 16 << 20,
            max_total_bytes: 256 << 20,
            max_ratio: 200,
            ratio_floor_bytes: 1 << 20,
            max_entries: 100_000,
        }
    }
}

/// Iris's map of dimensions to program folders, in `shaders/`.
const DIMENSION_PROPERTIES: &str = "dimension.properties";

/// The files of a pack's `shaders/` folder, in memory.
#[derive(Clone, Debug, Default)]
pub struct PackFiles {
    /// What the `shaders/` folder is called in messages (`pack/shaders/`, `pack.zip/shaders/`).
    pub display_root: String,
    /// Read from a zip (its files are in no folder a tool could open).
    pub archive: bool,
    /// Files by path relative to `shaders/` (`/` separators).
    pub files: BTreeMap<String, Arc<[u8]>>,
    /// Decoded text of the text files (shaders, includes, properties).
    pub texts: BTreeMap<String, Arc<str>>,
    /// What reading the pack found: skipped entries (warnings) and entries that could not be
    /// read (errors).
    pub warnings: Vec<Diagnostic>,
}

impl PackFiles {
    /// The world folder whose programs `loader` runs in `dimension` (`""`: the shaders folder).
    pub fn world_folder(&self, dimension: &Dimension, loader: Loader) -> String {
        let has_folder = |folder: &str| self.files.keys().any(|p| p.strip_prefix(folder).is_some_and(|rest| rest.starts_with('/')));
        crate::programs::world_folder(dimension, loader, &has_folder, &self.dimension_map(loader))
    }

    /// Iris's `dimension.properties` of the pack ([`crate::programs::dimension_map`]); empty
    /// under OptiFine, which has none.
    pub fn dimension_map(&self, loader: Loader) -> Vec<(String, String)> {
        match (loader, self.texts.get(DIMENSION_PROPERTIES)) {
            (Loader::Iris, Some(text)) => crate::programs::dimension_map(text),
            _ => Vec::new(),
        }
    }

    /// Every program of the pack's world folders ([`crate::programs::find_programs_in`]), with
    /// the folders `dimension.properties` names under Iris.
    pub fn programs(&self, loader: Loader) -> Vec<crate::programs::Program> {
        let named: Vec<String> = self.dimension_map(loader).into_iter().map(|(_, folder)| folder).collect();
        crate::programs::find_programs_in(self.files.keys(), &|folder| crate::programs::is_world_folder(folder) || named.iter().any(|n| n == folder))
    }
}

/// Extensions read as text: the stage files, the include extensions packs use (`.glsl`,
/// `.inc`, `.frag`, `.vert`, …), properties and language files.
const TEXT_EXTENSIONS: [&str; 17] = [
    "vsh", "fsh", "gsh", "csh", "tcs", "tes", "glsl", "inc", "h", "hlsl", "frag", "vert", "geom", "comp", "properties", "lang", "txt",
];

fn is_text(path: &str) -> bool {
    path.rsplit_once('.').is_some_and(|(_, ext)| TEXT_EXTENSIONS.contains(&ext.to_ascii_lowercase().as_str()))
}

/// Reads a pack folder or zip. An error means the input cannot be read at all (exit code 2).
pub fn read_pack(path: &Path, limits: &Limits) -> Result<PackFiles, Diagnostic> {
    let meta = std::fs::metadata(path)
        .map_err(|e| Diagnostic::error(Code::PackInput, format!("cannot read {}: {e}", path.display()), None))?;
    let mut raw = RawEntries::default();
    let shown = path.display().to_string();
    if meta.is_dir() {
        read_folder(path, "", limits, &mut raw, 0)?;
    } else if !meta.is_file() {
        // Opening a named pipe or a device would block or read without end.
        return Err(Diagnostic::error(Code::PackInput, format!("{} is neither a folder nor a regular file (a zip)", path.display()), None));
    } else {
        let file = std::fs::File::open(path)
            .map_err(|e| Diagnostic::error(Code::PackInput, format!("cannot open {}: {e}", path.display()), None))?;
        read_zip(file, &shown, limits, &mut raw)?;
    }
    into_pack(raw, &shown, !meta.is_dir())
}

/// Reads a zipped pack held in memory (`shown` names it in messages).
pub fn read_zip_bytes(bytes: &[u8], shown: &str, limits: &Limits) -> Result<PackFiles, Diagnostic> {
    let mut raw = RawEntries::default();
    read_zip(std::io::Cursor::new(bytes), shown, limits, &mut raw)?;
    into_pack(raw, shown, true)
}

/// The pack's `shaders/` folder out of everything read, its text decoded.
fn into_pack(raw: RawEntries, shown: &str, archive: bool) -> Result<PackFiles, Diagnostic> {
    let root = find_shaders_root(&raw.files).ok_or_else(|| {
        // Entries left out for their size or name may be the pack's whole shaders/ folder.
        let unread: Vec<&str> = raw.warnings.iter().map(|d| d.message.as_str()).collect();
        let message = if unread.is_empty() {
            format!("{shown} holds no shader pack: no `shaders/` folder at its root or inside one wrapper folder")
        } else {
            format!("{shown}: no readable `shaders/` folder; {} entries were left out, first: {}", unread.len(), unread[0])
        };
        Diagnostic::error(Code::PackInput, message, None)
    })?;
    let mut pack = PackFiles {
        display_root: format!("{}/{root}", shown.trim_end_matches('/')),
        archive,
        warnings: raw.warnings,
        ..Default::default()
    };
    for (name, bytes) in raw.files {
        let Some(rel) = name.strip_prefix(&root) else { continue };
        if rel.is_empty() {
            continue;
        }
        if is_text(rel) {
            let (text, warning) = decode(rel, &bytes);
            pack.warnings.extend(warning);
            pack.texts.insert(rel.to_string(), text);
        }
        pack.files.insert(rel.to_string(), bytes);
    }
    Ok(pack)
}

/// Builds a pack from in-memory files already relative to `shaders/` (tests, fuzzing).
pub fn pack_from_memory(display_root: &str, files: impl IntoIterator<Item = (String, Vec<u8>)>) -> PackFiles {
    let mut pack = PackFiles { display_root: display_root.to_string(), ..Default::default() };
    for (name, bytes) in files {
        if is_text(&name) {
            let (text, warning) = decode(&name, &bytes);
            pack.warnings.extend(warning);
            pack.texts.insert(name.clone(), text);
        }
        pack.files.insert(name, Arc::from(bytes));
    }
    pack
}

/// UTF-8 text without a byte-order mark, a lone carriage return read as a line end (GLSL ends
/// lines with CR, LF or CR LF, and OptiFine reads packs line by line); other bytes are replaced,
/// with a warning at the line of the first one.
fn decode(path: &str, bytes: &[u8]) -> (Arc<str>, Option<Diagnostic>) {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let (text, warning) = decode_utf8(path, bytes);
    if !text.contains('\r') {
        return (text, warning);
    }
    let mut unified = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        unified.push(if c == '\r' && chars.peek() != Some(&'\n') { '\n' } else { c });
    }
    (Arc::from(unified), warning)
}

/// The size `bytes` takes once decoded: replacement characters take three bytes each.
fn decoded_len(bytes: &[u8]) -> u64 {
    match std::str::from_utf8(bytes) {
        Ok(_) => bytes.len() as u64,
        Err(_) => String::from_utf8_lossy(bytes).len() as u64,
    }
}

fn decode_utf8(path: &str, bytes: &[u8]) -> (Arc<str>, Option<Diagnostic>) {
    match std::str::from_utf8(bytes) {
        Ok(text) => (Arc::from(text), None),
        Err(e) => {
            let at = e.valid_up_to();
            let line = bytes[..at].iter().filter(|&&b| b == b'\n').count() as u32 + 1;
            let warning = Diagnostic::warning(
                Code::BadUtf8,
                format!("not valid UTF-8 (byte {at}); the bad bytes are read as U+FFFD"),
                Some(Location::line(path, line)),
            )
            .with_note("outside comments such bytes are errors for every GLSL compiler; save the file as UTF-8");
            (Arc::from(String::from_utf8_lossy(bytes).as_ref()), Some(warning))
        }
    }
}

#[derive(Default)]
struct RawEntries {
    /// Paths relative to the input root.
    files: BTreeMap<String, Arc<[u8]>>,
    warnings: Vec<Diagnostic>,
    total: u64,
    entries: usize,
}

impl RawEntries {
    fn skip(&mut self, name: &str, why: String) {
        self.warnings.push(Diagnostic::warning(Code::SkippedFile, format!("skipped `{}`: {why}", name.escape_debug()), None));
    }

    /// An entry left unread for its size. Shader text the loader would read and this check
    /// cannot is an error, so a pack is never passed with programs unchecked; other files
    /// (textures) are skipped with a warning.
    fn too_large(&mut self, name: &str, why: String) {
        if is_text(name) {
            self.warnings.push(Diagnostic::error(Code::PackInput, format!("`{}` is not checked: {why}", name.escape_debug()), None));
        } else {
            self.skip(name, why);
        }
    }

    fn unreadable(&mut self, name: &str, why: String) {
        self.warnings.push(Diagnostic::error(Code::PackInput, format!("cannot read `{}`: {why}", name.escape_debug()), None));
    }

    /// Whether a file of `size` bytes at `path` may still fit the budget for the whole pack;
    /// says why not. Text is kept twice, as bytes and decoded.
    fn fits(&mut self, name: &str, path: &str, size: u64, limits: &Limits) -> bool {
        let cost = if is_text(path) { 2 * size } else { size };
        let fits = self.total + cost <= limits.max_total_bytes;
        if !fits {
            self.too_large(name, format!("the pack exceeds its budget of {} MiB in all", limits.max_total_bytes >> 20));
        }
        fits
    }

    /// Keeps the file if what it costs, decoded (a bad UTF-8 byte becomes three), fits the
    /// budget for the whole pack.
    fn keep(&mut self, name: &str, path: String, bytes: Vec<u8>, limits: &Limits) {
        let cost = bytes.len() as u64 + if is_text(&path) { decoded_len(&bytes) } else { 0 };
        if self.total + cost > limits.max_total_bytes {
            self.too_large(name, format!("the pack exceeds its budget of {} MiB in all, decoded", limits.max_total_bytes >> 20));
            return;
        }
        self.total += cost;
        self.files.insert(path, Arc::from(bytes));
    }

    /// A file whose data is damaged: shader text nobody can check fails the pack.
    fn damaged(&mut self, name: &str, why: String) {
        if is_text(name) {
            self.unreadable(name, why);
        } else {
            self.skip(name, why);
        }
    }
}

fn read_folder(dir: &Path, rel: &str, limits: &Limits, raw: &mut RawEntries, depth: usize) -> Result<(), Diagnostic> {
    if depth > 32 {
        raw.skip(rel, "folders nest deeper than 32 levels".into());
        return Ok(());
    }
    let entries = std::fs::read_dir(dir).map_err(|e| Diagnostic::error(Code::PackInput, format!("cannot list {}: {e}", dir.display()), None))?;
    let mut names: Vec<_> = entries.filter_map(Result::ok).collect();
    names.sort_by_key(|e| e.file_name());
    for entry in names {
        raw.entries += 1;
        if raw.entries > limits.max_entries {
            return Err(Diagnostic::error(Code::PackInput, format!("more than {} files and folders: not read", limits.max_entries), None));
        }
        let name = entry.file_name().to_string_lossy().into_owned();
        let path = if rel.is_empty() { name.clone() } else { format!("{rel}/{name}") };
        let Ok(kind) = entry.file_type() else { continue };
        if kind.is_symlink() {
            raw.skip(&path, "symbolic links are not followed".into());
        } else if kind.is_dir() {
            read_folder(&entry.path(), &path, limits, raw, depth + 1)?;
        } else if kind.is_file() {
            let size = entry.metadata().map_or(0, |m| m.len());
            if size > limits.max_file_bytes {
                raw.too_large(&path, format!("{size} bytes, more than the {} MiB limit for one file", limits.max_file_bytes >> 20));
                continue;
            }
            if !raw.fits(&path, &path, size, limits) {
                continue;
            }
            // The file may have grown since its size was read: never read past the limit.
            let mut bytes = Vec::with_capacity(size.min(1 << 20) as usize);
            match std::fs::File::open(entry.path()).and_then(|f| f.take(limits.max_file_bytes + 1).read_to_end(&mut bytes)) {
                Ok(_) if bytes.len() as u64 > limits.max_file_bytes => {
                    raw.too_large(&path, format!("more than the {} MiB limit for one file", limits.max_file_bytes >> 20));
                }
                Ok(_) => raw.keep(&path.clone(), path, bytes, limits),
                Err(e) => raw.damaged(&path, format!("{e}")),
            }
        }
    }
    Ok(())
}

/// A zip entry name as a safe relative path, or why it is not one.
fn safe_entry_name(name: &str) -> Result<String, &'static str> {
    let name = name.replace('\\', "/");
    if name.starts_with('/') || name.chars().nth(1) == Some(':') {
        return Err("absolute path");
    }
    let mut parts = Vec::new();
    for part in name.split('/') {
        match part {
            "" | "." => {}
            ".." => return Err("path climbs out with `..`"),
            p if p.chars().any(char::is_control) => return Err("control character in the name"),
            p => parts.push(p),
        }
    }
    if parts.is_empty() {
        return Err("empty name");
    }
    Ok(parts.join("/"))
}

fn read_zip<R: Read + Seek>(mut reader: R, shown: &str, limits: &Limits, raw: &mut RawEntries) -> Result<(), Diagnostic> {
    let unreadable = |e: zip::result::ZipError| Diagnostic::error(Code::PackInput, format!("{shown} is neither a folder nor a readable zip: {e}"), None);
    let duplicates = {
        let archive = zip::ZipArchive::new(&mut reader).map_err(unreadable)?;
        archive.has_duplicate_names().then(|| archive.central_directory_start())
    };
    if let Some(start) = duplicates {
        for (name, count) in duplicate_names(&mut reader, start) {
            let message = format!("`{}` appears {count} times in the zip; loaders read only the last copy, as this check does", name.escape_debug());
            raw.warnings.push(Diagnostic::warning(Code::DuplicateEntry, message, None));
        }
    }
    let mut archive = zip::ZipArchive::new(reader).map_err(unreadable)?;
    if archive.len() > limits.max_entries {
        return Err(Diagnostic::error(Code::PackInput, format!("{shown} has {} entries, more than {}: not read", archive.len(), limits.max_entries), None));
    }
    for index in 0..archive.len() {
        // A pack file that cannot be read is a file nobody checked: an error, not a warning.
        if let Ok(raw_entry) = archive.by_index_raw(index)
            && !raw_entry.is_dir()
        {
            let method = raw_entry.compression();
            let why = if raw_entry.encrypted() {
                Some("encrypted (OptiFine cannot read it either)".to_string())
            } else if !matches!(method, zip::CompressionMethod::Stored | zip::CompressionMethod::Deflated) {
                #[allow(deprecated)] // The method's number is what names an unsupported one.
                let method = zip::CompressionMethod::name_from_u16(method.to_u16());
                Some(format!("compressed with {method}, which tidepack does not read (OptiFine reads only stored and deflated entries); re-zip the pack with deflate"))
            } else {
                None
            };
            if let Some(why) = why {
                let name = raw_entry.name().map(|n| n.to_string()).unwrap_or_else(|_| format!("entry #{index}"));
                raw.unreadable(&name, why);
                continue;
            }
        }
        let mut entry = match archive.by_index(index) {
            Ok(entry) => entry,
            Err(e) => {
                raw.skip(&format!("entry #{index}"), format!("unreadable: {e}"));
                continue;
            }
        };
        let name = match entry.name() {
            Ok(name) => name.to_string(),
            Err(e) => {
                raw.skip(&format!("entry #{index}"), format!("unreadable name: {e}"));
                continue;
            }
        };
        if entry.is_dir() {
            continue;
        }
        let path = match safe_entry_name(&name) {
            Ok(path) => path,
            Err(why) => {
                raw.skip(&name, format!("unsafe entry name ({why}); never extracted"));
                continue;
            }
        };
        if entry.is_symlink() {
            // Loaders read an entry's data whatever its Unix mode: a link's data is its target.
            let why = "a symbolic link entry: loaders read the link's target path as the file's text".to_string();
            raw.damaged(&name, why);
            continue;
        }
        let (size, compressed) = (entry.size(), entry.compressed_size());
        if size > limits.max_file_bytes {
            raw.too_large(&name, format!("{size} bytes uncompressed, more than the {} MiB limit for one file", limits.max_file_bytes >> 20));
            continue;
        }
        if size > limits.ratio_floor_bytes && size / compressed.max(1) > limits.max_ratio {
            raw.too_large(&name, format!("compression ratio {}:1 looks like a zip bomb", size / compressed.max(1)));
            continue;
        }
        if !raw.fits(&name, &path, size, limits) {
            continue;
        }
        // The header's size may lie: never read more than the limit.
        let mut bytes = Vec::with_capacity(size.min(1 << 20) as usize);
        match (&mut entry).take(limits.max_file_bytes + 1).read_to_end(&mut bytes) {
            Ok(_) if bytes.len() as u64 > limits.max_file_bytes || bytes.len() as u64 != size => {
                let why = format!("the zip is damaged: the entry's data ({}+ bytes) does not match the size its header claims ({size})", bytes.len());
                raw.damaged(&name, why);
            }
            Ok(_) => raw.keep(&name, path, bytes, limits),
            Err(e) => raw.damaged(&name, format!("the zip is damaged: {e}")),
        }
    }
    Ok(())
}

/// Names the central directory holds more than once, with their counts. The zip reader keeps
/// the last entry of each name, as Java's readers do, so the others are never read.
fn duplicate_names<R: Read + Seek>(reader: &mut R, start: u64) -> Vec<(String, usize)> {
    use std::io::SeekFrom;
    const CENTRAL_HEADER: [u8; 4] = [0x50, 0x4b, 0x01, 0x02];
    let mut directory = Vec::new();
    if reader.seek(SeekFrom::Start(start)).is_err() || reader.take(64 << 20).read_to_end(&mut directory).is_err() {
        return Vec::new();
    }
    let mut counts: BTreeMap<Vec<u8>, usize> = BTreeMap::new();
    let mut at = 0;
    while directory.len() >= at + 46 && directory[at..at + 4] == CENTRAL_HEADER {
        let field = |offset: usize| usize::from(u16::from_le_bytes([directory[at + offset], directory[at + offset + 1]]));
        let (name_len, extra_len, comment_len) = (field(28), field(30), field(32));
        let Some(name) = directory.get(at + 46..at + 46 + name_len) else { break };
        *counts.entry(name.to_vec()).or_default() += 1;
        at += 46 + name_len + extra_len + comment_len;
    }
    counts.into_iter().filter(|(_, n)| *n > 1).map(|(name, n)| (String::from_utf8_lossy(&name).into_owned(), n)).collect()
}

/// `shaders/` at the root, inside exactly one wrapper folder, or the input is the `shaders`
/// folder itself. Returns the prefix (`shaders/`, `Wrapper/shaders/` or ``).
fn find_shaders_root(files: &BTreeMap<String, Arc<[u8]>>) -> Option<String> {
    if files.keys().any(|p| p.starts_with("shaders/")) {
        return Some("shaders/".into());
    }
    let tops: std::collections::BTreeSet<&str> = files.keys().filter_map(|p| p.split_once('/').map(|(t, _)| t)).collect();
    let wrapped: Vec<&&str> = tops.iter().filter(|t| files.keys().any(|p| p.starts_with(&format!("{t}/shaders/")))).collect();
    if let [wrapper] = wrapped.as_slice() {
        return Some(format!("{wrapper}/shaders/"));
    }
    let looks_like_shaders = files.keys().any(|p| {
        p == "shaders.properties" || (!p.contains('/') && (p.ends_with(".vsh") || p.ends_with(".fsh")))
            || (p.starts_with("world") && (p.ends_with(".vsh") || p.ends_with(".fsh")))
    });
    looks_like_shaders.then(String::new)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn zip_of(entries: &[(&str, &[u8])]) -> Vec<u8> {
        let mut buf = std::io::Cursor::new(Vec::new());
        let mut zip = zip::ZipWriter::new(&mut buf);
        for (name, data) in entries {
            zip.start_file(*name, zip::write::SimpleFileOptions::default()).unwrap();
            zip.write_all(data).unwrap();
        }
        zip.finish().unwrap();
        buf.into_inner()
    }

    #[test]
    fn unsafe_zip_names_are_skipped_not_written() {
        let data = zip_of(&[
            ("shaders/final.fsh", b"#version 120\nvoid main() {}\n"),
            ("shaders/../../evil.fsh", b"x"),
            ("/etc/passwd", b"x"),
            ("C:\\\\windows\\\\x.fsh", b"x"),
        ]);
        let mut raw = RawEntries::default();
        read_zip(std::io::Cursor::new(data), "t.zip", &Limits::default(), &mut raw).unwrap();
        assert_eq!(raw.files.keys().collect::<Vec<_>>(), ["shaders/final.fsh"]);
        assert_eq!(raw.warnings.len(), 3, "{:?}", raw.warnings);
        assert!(raw.warnings.iter().all(|w| w.message.contains("unsafe entry name")));
    }

    #[test]
    fn zip_bombs_are_refused_by_ratio_and_size() {
        let zeros = vec![0u8; 4 << 20];
        let data = zip_of(&[("shaders/bomb.glsl", &zeros), ("shaders/final.fsh", b"void main() {}\n")]);
        let mut raw = RawEntries::default();
        read_zip(std::io::Cursor::new(data.clone()), "t.zip", &Limits::default(), &mut raw).unwrap();
        assert!(!raw.files.contains_key("shaders/bomb.glsl"));
        assert!(raw.warnings[0].message.contains("zip bomb"), "{:?}", raw.warnings);
        let small = Limits { max_file_bytes: 1 << 20, ..Limits::default() };
        let mut raw = RawEntries::default();
        read_zip(std::io::Cursor::new(data), "t.zip", &small, &mut raw).unwrap();
        assert!(raw.warnings[0].message.contains("limit for one file"), "{:?}", raw.warnings);
        // Shader text left unchecked fails the pack; a texture too large is only skipped.
        assert!(raw.warnings[0].is_error(), "{:?}", raw.warnings);
        let data = zip_of(&[("shaders/noise.png", &zeros), ("shaders/final.fsh", b"void main() {}\n")]);
        let mut raw = RawEntries::default();
        read_zip(std::io::Cursor::new(data), "t.zip", &small, &mut raw).unwrap();
        assert!(!raw.warnings[0].is_error() && raw.warnings[0].message.contains("skipped"), "{:?}", raw.warnings);
    }

    #[test]
    fn a_pack_whose_shaders_were_all_left_out_says_why() {
        let zeros = vec![0u8; 4 << 20];
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("one.zip");
        std::fs::write(&path, zip_of(&[("shaders/composite.fsh", &zeros)])).unwrap();
        let err = read_pack(&path, &Limits::default()).unwrap_err();
        assert!(err.message.contains("left out") && err.message.contains("shaders/composite.fsh"), "{}", err.message);
    }

    fn stored_zip_of(entries: &[(&str, &[u8])]) -> Vec<u8> {
        let mut buf = std::io::Cursor::new(Vec::new());
        let mut zip = zip::ZipWriter::new(&mut buf);
        for (name, data) in entries {
            let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
            zip.start_file(*name, options).unwrap();
            zip.write_all(data).unwrap();
        }
        zip.finish().unwrap();
        buf.into_inner()
    }

    fn read(data: Vec<u8>) -> RawEntries {
        let mut raw = RawEntries::default();
        read_zip(std::io::Cursor::new(data), "t.zip", &Limits::default(), &mut raw).unwrap();
        raw
    }

    fn replace_all(data: &mut [u8], from: &[u8], to: &[u8]) {
        for i in 0..data.len() - from.len() {
            if &data[i..i + from.len()] == from {
                data[i..i + to.len()].copy_from_slice(to);
            }
        }
    }

    #[test]
    fn a_damaged_program_fails_the_pack() {
        let mut data = stored_zip_of(&[("shaders/composite.fsh", b"void main() { gl_FragColor = vec4(1.0); }\n")]);
        replace_all(&mut data, b"gl_FragColor", b"GL_FragColor");
        let raw = read(data);
        assert!(raw.files.is_empty());
        assert!(raw.warnings[0].is_error() && raw.warnings[0].message.contains("the zip is damaged"), "{:?}", raw.warnings);
    }

    #[test]
    fn an_entry_longer_than_its_header_says_fails_the_pack() {
        let text = b"void main() { gl_FragColor = vec4(1.0); }\n";
        let mut data = stored_zip_of(&[("shaders/composite.fsh", text)]);
        // The uncompressed size in the local header (offset 22) and the central header (24).
        let size = (text.len() as u32).to_le_bytes();
        let short = (text.len() as u32 - 10).to_le_bytes();
        data[22..26].copy_from_slice(&short);
        let central = (0..data.len() - 4).find(|&i| data[i..i + 4] == [0x50, 0x4b, 0x01, 0x02]).unwrap();
        assert_eq!(data[central + 24..central + 28], size);
        data[central + 24..central + 28].copy_from_slice(&short);
        let raw = read(data);
        assert!(raw.files.is_empty());
        assert!(raw.warnings[0].is_error() && raw.warnings[0].message.contains("the zip is damaged"), "{:?}", raw.warnings);
    }

    #[test]
    fn a_symbolic_link_program_fails_the_pack() {
        let mut buf = std::io::Cursor::new(Vec::new());
        let mut zip = zip::ZipWriter::new(&mut buf);
        zip.add_symlink("shaders/composite.fsh", "../../../etc/passwd", zip::write::SimpleFileOptions::default()).unwrap();
        zip.finish().unwrap();
        let raw = read(buf.into_inner());
        assert!(raw.files.is_empty());
        assert!(raw.warnings[0].is_error() && raw.warnings[0].message.contains("symbolic link"), "{:?}", raw.warnings);
    }

    #[test]
    fn a_name_twice_in_the_zip_is_named() {
        let mut data = stored_zip_of(&[("shaders/composite.fsh", b"first\n"), ("shaders/compositX.fsh", b"second\n")]);
        replace_all(&mut data, b"compositX", b"composite");
        let raw = read(data);
        assert_eq!(&*raw.files["shaders/composite.fsh"], b"second\n");
        assert!(raw.warnings[0].message.contains("`shaders/composite.fsh` appears 2 times"), "{:?}", raw.warnings);
    }

    #[test]
    fn unsupported_compression_is_named() {
        let mut data = stored_zip_of(&[("shaders/composite.fsh", b"void main() {}\n")]);
        // Method 12 (bzip2) in the local header (offset 8) and the central header (offset 10).
        data[8] = 12;
        let central = (0..data.len() - 4).find(|&i| data[i..i + 4] == [0x50, 0x4b, 0x01, 0x02]).unwrap();
        data[central + 10] = 12;
        let raw = read(data);
        assert!(raw.warnings[0].is_error() && raw.warnings[0].message.contains("compressed with Bzip2"), "{:?}", raw.warnings);
    }

    #[test]
    fn bad_utf8_counts_decoded_against_the_budget() {
        let bad = vec![0xFFu8; 1 << 20];
        let limits = Limits { max_total_bytes: 3 << 20, ratio_floor_bytes: u64::MAX, ..Limits::default() };
        let mut raw = RawEntries::default();
        // 1 MiB of bad bytes decodes to 3 MiB: 4 MiB in all, over the 3 MiB budget.
        read_zip(std::io::Cursor::new(zip_of(&[("shaders/a.glsl", &bad)])), "t.zip", &limits, &mut raw).unwrap();
        assert!(raw.files.is_empty());
        assert!(raw.warnings[0].is_error() && raw.warnings[0].message.contains("budget"), "{:?}", raw.warnings);
    }

    #[cfg(unix)]
    #[test]
    fn a_named_pipe_is_refused_without_opening_it() {
        let dir = tempfile::tempdir().unwrap();
        let pipe = dir.path().join("pack.zip");
        let status = std::process::Command::new("mkfifo").arg(&pipe).status().unwrap();
        assert!(status.success());
        let err = read_pack(&pipe, &Limits::default()).unwrap_err();
        assert!(err.message.contains("neither a folder nor a regular file"), "{}", err.message);
    }

    #[test]
    fn garbage_is_unreadable_input() {
        let mut raw = RawEntries::default();
        let err = read_zip(std::io::Cursor::new(b"not a zip".to_vec()), "t.zip", &Limits::default(), &mut raw).unwrap_err();
        assert!(err.message.contains("neither a folder nor a readable zip"), "{err}");
    }

    #[test]
    fn finds_the_shaders_folder() {
        let files = |names: &[&str]| -> BTreeMap<String, Arc<[u8]>> {
            names.iter().map(|n| (n.to_string(), Arc::from(&b""[..]))).collect()
        };
        assert_eq!(find_shaders_root(&files(&["shaders/final.fsh"])), Some("shaders/".into()));
        assert_eq!(find_shaders_root(&files(&["Pack v1/shaders/final.fsh", "Pack v1/readme.txt"])), Some("Pack v1/shaders/".into()));
        assert_eq!(find_shaders_root(&files(&["final.fsh", "lib/a.glsl"])), Some(String::new()));
        assert_eq!(find_shaders_root(&files(&["a/shaders/x.fsh", "b/shaders/y.fsh"])), None);
        assert_eq!(find_shaders_root(&files(&["readme.txt"])), None);
    }

    #[test]
    fn non_utf8_and_bom_decode_with_a_warning() {
        let (text, warning) = decode("a.fsh", b"\xEF\xBB\xBF// caf\xE9\nvoid main() {}\n");
        assert!(text.starts_with("// caf\u{FFFD}"));
        assert_eq!(warning.unwrap().location.unwrap().line, 1);
        let (text, warning) = decode("a.fsh", b"\xEF\xBB\xBFvoid main() {}\n");
        assert_eq!(&*text, "void main() {}\n");
        assert!(warning.is_none());
    }

    #[test]
    fn a_lone_carriage_return_ends_a_line() {
        let (text, _) = decode("a.fsh", b"#version 120\rvoid main() {}\r\n// end\r");
        assert_eq!(&*text, "#version 120\nvoid main() {}\r\n// end\n");
    }
}
