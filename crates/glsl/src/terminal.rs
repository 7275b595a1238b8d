//! Text bound for a terminal, made inert. A pack, a scene or a command line can carry control
//! characters (an escape sequence that recolours or clears the screen, a carriage return that
//! overwrites a line, a line break that forges an `error:` line) and Unicode's bidirectional
//! controls (which reorder what is shown). Every line tidepack prints passes through one of
//! these functions: [`crate::diagnostic::emit`] applies them to diagnostics, and the CLI's
//! printing macros to everything else.

/// Whether `c` changes how the text around it is shown: the bidirectional embeddings,
/// overrides and isolates.
fn is_bidi_control(c: char) -> bool {
    matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}' | '\u{200E}' | '\u{200F}' | '\u{061C}')
}

fn push_escaped(out: &mut String, c: char) {
    match c {
        c if (c as u32) < 0x20 => {
            out.push('^');
            out.push(char::from(b'@' + c as u8));
        }
        '\u{7f}' => out.push_str("^?"),
        c => out.push_str(&format!("<U+{:04X}>", c as u32)),
    }
}

fn needs_escape(c: char) -> bool {
    c.is_control() || is_bidi_control(c)
}

/// Text of several lines: line breaks and tabs stay, every other control character is shown
/// in caret notation (`^[`, `^M`) or as `<U+202E>`.
pub fn block(text: &str) -> String {
    escaped(text, |c| c != '\n' && c != '\t' && needs_escape(c))
}

/// Text that must stay on one line (a name or value from a pack inside a message): line breaks
/// are shown as `^J` too.
pub fn line(text: &str) -> String {
    escaped(text, |c| c != '\t' && needs_escape(c))
}

fn escaped(text: &str, escape: impl Fn(char) -> bool) -> String {
    if !text.chars().any(&escape) {
        return text.to_string();
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if escape(c) {
            push_escaped(&mut out, c);
        } else {
            out.push(c);
        }
    }
    out
}

/// A source file shown in a snippet, made safe without moving any byte: each byte of a control
/// character becomes `?`, so a diagnostic's byte columns still point at their text.
pub fn source(text: &str) -> String {
    if !text.chars().any(|c| c != '\n' && c != '\t' && c != '\r' && needs_escape(c)) {
        return text.to_string();
    }
    text.chars()
        .map(|c| match c {
            '\t' | '\n' | '\r' => c.to_string(),
            c if needs_escape(c) => "?".repeat(c.len_utf8()),
            c => c.to_string(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_shown_not_acted_on() {
        assert_eq!(block("a\x1b[2Jb\tc\nd\re"), "a^[[2Jb\tc\nd^Me");
        assert_eq!(line("name\r\nerror: forged"), "name^M^Jerror: forged");
        assert_eq!(line("abc\u{202E}def"), "abc<U+202E>def");
        assert_eq!(block("\u{7f}\u{85}"), "^?<U+0085>");
        assert_eq!(line("plain text"), "plain text");
    }

    #[test]
    fn a_source_keeps_its_byte_offsets() {
        let text = "x\u{1b}y\u{202E}z\n";
        let safe = source(text);
        assert_eq!(safe.len(), text.len());
        assert_eq!(safe, "x?y???z\n");
    }
}
