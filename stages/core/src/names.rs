//! Names from files others made (a plant model's groups, a survey's scans),
//! as liftplan keeps them for its words: printed in the run's lines, drawn
//! on the plan's pages, written in its CSV and JSON files.
//!
//! A file can state a name of any length holding any character (an RVM
//! group, an E57 scan's name, a scan file's own name); a name of thousands
//! of characters would fill the pages, and a line break or a terminal's
//! escape in one would print lines it does not say. [`kept`] bounds a name
//! and shows its control characters as U+FFFD, and tags a name it shortens
//! with its hash, so two that agree in their first characters still read
//! apart. This module must not be used to match names: selections and
//! station files match the name as the file states it, or both sides kept.

use std::borrow::Cow;

/// How many characters [`kept`] adds after a long name's first characters:
/// "... #" and eight hex digits of the whole name's BLAKE3 hash.
pub const TAG_CHARS: usize = 13;

/// `name` as liftplan keeps it: whole up to `max_chars` characters, else
/// its first `max_chars`, "... #" and the first eight hex digits of the
/// whole name's BLAKE3 hash ([`TAG_CHARS`] more); each control character
/// shown as U+FFFD. A name kept is kept again unchanged.
pub fn kept(name: &str, max_chars: usize) -> Cow<'_, str> {
    let cut = name.char_indices().nth(max_chars).map(|(at, _)| at);
    let (head, tail) = match cut {
        None => (name, Cow::Borrowed("")),
        Some(at) if is_tag(&name[at..]) => (&name[..at], Cow::Borrowed(&name[at..])),
        Some(at) => {
            let hash = blake3::hash(name.as_bytes()).to_hex();
            (&name[..at], Cow::Owned(format!("... #{}", &hash[..8])))
        }
    };
    match (without_controls(head), tail) {
        (Cow::Borrowed(_), Cow::Borrowed(_)) => Cow::Borrowed(name),
        (head, tail) => Cow::Owned(head.into_owned() + &tail),
    }
}

/// Text from a file of no stated encoding (an RVM file's names, an ATT
/// file's lines): as UTF-8 where the bytes are UTF-8, which AVEVA E3D and
/// other tools of today write; else as Latin-1, one character a byte, as
/// PDMS wrote them. Latin-1 text other than ASCII is almost never valid
/// UTF-8 (a lone accented letter is not), so the two are told apart
/// without a setting; the same bytes always give the same text, so names
/// matched across files (an RVM group and its ATT block) still match.
pub fn utf8_or_latin1(bytes: &[u8]) -> Cow<'_, str> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Cow::Borrowed(text),
        Err(_) => Cow::Owned(bytes.iter().map(|&b| b as char).collect()),
    }
}

/// `words` with each control character shown as U+FFFD, whole.
pub fn without_controls(words: &str) -> Cow<'_, str> {
    if !words.chars().any(char::is_control) {
        return Cow::Borrowed(words);
    }
    Cow::Owned(words.chars().map(|c| if c.is_control() { '\u{FFFD}' } else { c }).collect())
}

/// Whether `tail` is what [`kept`] puts after a long name's first
/// characters.
fn is_tag(tail: &str) -> bool {
    tail.len() == TAG_CHARS
        && tail.starts_with("... #")
        && tail[5..].bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
}

#[cfg(test)]
mod tests {
    use super::{TAG_CHARS, kept, utf8_or_latin1};

    #[test]
    fn text_is_utf8_where_it_is_else_latin1() {
        assert_eq!(utf8_or_latin1(b"/PIPE-RACK-2"), "/PIPE-RACK-2");
        assert_eq!(utf8_or_latin1("/BEHÄLTER-Ø2".as_bytes()), "/BEHÄLTER-Ø2");
        assert_eq!(utf8_or_latin1(b"/BEH\xc4LTER-\xd82"), "/BEHÄLTER-Ø2");
    }

    #[test]
    fn names_kept_bounded_without_control_characters_and_apart() {
        let kept = |name: &str| kept(name, 200).into_owned();
        assert_eq!(kept("/PIPE-RACK-2"), "/PIPE-RACK-2");
        let longest = "é".repeat(200);
        assert_eq!(kept(&longest), longest);
        let longer = format!("{longest}x");
        let tag = |name: &str| format!("... #{}", &blake3::hash(name.as_bytes()).to_hex()[..8]);
        assert_eq!(kept(&longer), format!("{longest}{}", tag(&longer)));
        let very_long = kept(&"/A".repeat(50_000));
        assert_eq!(very_long.chars().count(), 200 + TAG_CHARS);
        assert_eq!(kept(&very_long), very_long);
        assert_eq!(kept("/V-1\x1b[2J\n\0"), "/V-1\u{FFFD}[2J\u{FFFD}\u{FFFD}");
        // Two names that agree in their first 200 characters read apart.
        let (a, b) = (format!("{longer}\n"), format!("{longer}y"));
        let (kept_a, kept_b) = (kept(&a), kept(&b));
        assert_eq!(kept_a, format!("{longest}{}", tag(&a)));
        assert_ne!(kept_a, kept_b);
        assert_eq!(kept(&kept_a), kept_a);
        // A control character before the tag is replaced, the tag kept.
        let rest: String = kept_a.chars().skip(1).collect();
        assert_eq!(kept(&format!("\x1b{rest}")), format!("\u{FFFD}{rest}"));
        // Words that only look like a tag past the 200th character, longer
        // than one, get one of their own.
        let not_a_tag = format!("{longest}... #0123456789");
        assert_eq!(kept(&not_a_tag), format!("{longest}{}", tag(&not_a_tag)));
        assert_eq!(super::kept("", 200), "");
    }
}
