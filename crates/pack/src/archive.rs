//! The pack zips: deterministic and written all or nothing.
//!
//! Entries are sorted and carry a fixed timestamp and permissions, so identical inputs give
//! byte-identical zips. Every zip of a build is first written to a temporary file beside its
//! target; only when all of them are complete are they renamed into place, so a failed or
//! interrupted build never leaves a partial zip, nor one dialect's zip without the other's.

use std::io::Write;
use std::path::{Path, PathBuf};

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// One zip to write: its target path and its entries (path inside the zip, contents).
pub type ZipContents<'a> = (PathBuf, Vec<(String, &'a [u8])>);

/// Why [`write_zips`] failed, and which targets it had already renamed into place (empty
/// unless a rename failed after others succeeded).
#[derive(Debug)]
pub struct WriteFailure {
    pub message: String,
    pub written: Vec<PathBuf>,
}

/// Writes every zip to a temporary file beside its target, then renames them all into place;
/// returns their sizes. A target that is a folder is refused before anything is written, and
/// the temporary files are removed on any failure.
pub fn write_zips(zips: &[ZipContents]) -> Result<Vec<u64>, WriteFailure> {
    let fail = |message: String| WriteFailure { message, written: Vec::new() };
    let mut temps: Vec<(PathBuf, &Path)> = Vec::new();
    let remove_temps = |temps: &[(PathBuf, &Path)]| {
        for (temp, _) in temps {
            let _ = std::fs::remove_file(temp);
        }
    };
    for (target, entries) in zips {
        let result = temp_path(target).and_then(|temp| {
            if target.is_dir() {
                return Err(std::io::Error::other("a folder of that name is in the way"));
            }
            temps.push((temp.clone(), target));
            write_to(&temp, entries)
        });
        if let Err(e) = result {
            remove_temps(&temps);
            return Err(fail(format!("cannot write {}: {e}", target.display())));
        }
    }
    let mut written = Vec::new();
    for (i, (temp, target)) in temps.iter().enumerate() {
        if let Err(e) = std::fs::rename(temp, target) {
            remove_temps(&temps[i..]);
            return Err(WriteFailure { message: format!("cannot rename {} to {}: {e}", temp.display(), target.display()), written });
        }
        written.push(target.to_path_buf());
    }
    written
        .iter()
        .map(|target| std::fs::metadata(target).map(|m| m.len()))
        .collect::<std::io::Result<Vec<u64>>>()
        .map_err(|e| WriteFailure { message: format!("cannot read back a written zip: {e}"), written: written.clone() })
}

/// `<dir>/.<name>.<pid>.tmp` beside `target`, creating `dir`.
fn temp_path(target: &Path) -> std::io::Result<PathBuf> {
    let dir = target.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let file_name = target.file_name().ok_or_else(|| std::io::Error::other("the zip path names no file"))?;
    Ok(dir.join(format!(".{}.{}.tmp", file_name.to_string_lossy(), std::process::id())))
}

fn write_to(path: &Path, entries: &[(String, &[u8])]) -> std::io::Result<()> {
    let mut sorted: Vec<&(String, &[u8])> = entries.iter().collect();
    sorted.sort_by(|a, b| a.0.cmp(&b.0));
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .compression_level(Some(9))
        .last_modified_time(DateTime::default())
        .unix_permissions(0o644);
    let mut zip = ZipWriter::new(std::fs::File::create(path)?);
    for (name, data) in sorted {
        zip.start_file(name.as_str(), options).map_err(std::io::Error::other)?;
        zip.write_all(data)?;
    }
    let file = zip.finish().map_err(std::io::Error::other)?;
    file.sync_all()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_inputs_give_identical_bytes() {
        let dir = std::env::temp_dir().join(format!("tidepack-archive-{}", std::process::id()));
        let a = dir.join("a.zip");
        let b = dir.join("b.zip");
        let entries = vec![("shaders/b.txt".to_string(), &b"two"[..]), ("shaders/a.txt".to_string(), &b"one"[..])];
        write_zips(&[(a.clone(), entries.clone())]).unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1100));
        let mut reversed = entries.clone();
        reversed.reverse();
        write_zips(&[(b.clone(), reversed)]).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
        let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).filter(|e| e.file_name().to_string_lossy().ends_with(".tmp")).collect();
        assert!(leftovers.is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failing_zip_leaves_no_zip_and_no_temporary_file() {
        let dir = tempfile_dir("all-or-nothing");
        let first = dir.join("first.zip");
        let blocked = dir.join("second.zip");
        std::fs::create_dir_all(&blocked).unwrap();
        let entries = vec![("a.txt".to_string(), &b"one"[..])];
        let failure = write_zips(&[(first.clone(), entries.clone()), (blocked.clone(), entries)]).unwrap_err();
        assert!(failure.message.contains("second.zip") && failure.message.contains("folder"), "{}", failure.message);
        assert!(failure.written.is_empty());
        assert!(!first.exists(), "the first zip was written although the second failed");
        let names: Vec<String> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        assert_eq!(names, ["second.zip"], "only the folder in the way remains");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn tempfile_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("tidepack-archive-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }
}
