//! A pack's files read under one option set, as OptiFine hands them to the preprocessor.

use std::collections::{BTreeMap, HashMap};
use std::sync::{Arc, Mutex};

use crate::option_lines::{self, OptionSet};
use tidepack_glsl::preprocess::FileProvider;

use crate::input::PackFiles;

/// A pack's files with one option set applied, as OptiFine rewrites the option lines.
pub struct SetProvider<'a> {
    pack: &'a PackFiles,
    set: &'a OptionSet,
    cache: Mutex<HashMap<String, Arc<str>>>,
    ignore_case: bool,
    read_by_case: Mutex<BTreeMap<String, String>>,
}

impl<'a> SetProvider<'a> {
    pub fn new(pack: &'a PackFiles, set: &'a OptionSet) -> Self {
        SetProvider { pack, set, cache: Mutex::new(HashMap::new()), ignore_case: false, read_by_case: Mutex::new(BTreeMap::new()) }
    }

    /// Reads a path the pack lacks from a file whose name differs only in case, as Windows'
    /// file system gives a pack folder to OptiFine (zips, Iris's folders on Linux and macOS
    /// refuse it). Each such read is kept ([`SetProvider::read_by_case`]).
    pub fn ignoring_case(self) -> Self {
        SetProvider { ignore_case: true, ..self }
    }

    /// The paths read from a file whose name differs only in case, each with that file's.
    pub fn read_by_case(&self) -> BTreeMap<String, String> {
        self.read_by_case.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }
}

impl FileProvider for SetProvider<'_> {
    fn read(&self, path: &str) -> Result<Arc<str>, String> {
        if let Some(text) = self.cache.lock().unwrap_or_else(|e| e.into_inner()).get(path) {
            return Ok(text.clone());
        }
        let decoded;
        let text = match (self.pack.texts.get(path), self.pack.files.get(path)) {
            (Some(text), _) => text,
            // OptiFine includes a file of any name (`Common.vert`, `lib.inc`): read it as text.
            (None, Some(bytes)) => match std::str::from_utf8(bytes) {
                Ok(text) => {
                    decoded = Arc::from(text);
                    &decoded
                }
                Err(e) => return Err(format!("not a text file: byte {} is not UTF-8", e.valid_up_to())),
            },
            (None, None) => {
                let lower = path.to_lowercase();
                return match self.pack.files.keys().find(|p| p.to_lowercase() == lower) {
                    Some(p) if self.ignore_case => {
                        let text = self.read(p)?;
                        self.read_by_case.lock().unwrap_or_else(|e| e.into_inner()).insert(path.to_string(), p.clone());
                        Ok(text)
                    }
                    Some(p) => Err(format!("no such file in the pack; `{p}` differs only in case (Iris and Linux are case-sensitive)")),
                    None => Err("no such file in the pack".into()),
                };
            }
        };
        let text: Arc<str> = match option_lines::apply(text, self.set) {
            std::borrow::Cow::Borrowed(_) => text.clone(),
            std::borrow::Cow::Owned(t) => Arc::from(t),
        };
        self.cache.lock().unwrap_or_else(|e| e.into_inner()).insert(path.to_string(), text.clone());
        Ok(text)
    }
}
