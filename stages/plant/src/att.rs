//! Reader for the `.att` attribute files PDMS writes beside an RVM export.
//!
//! ```text
//! CADC_Attributes_File v1.0 , start: NEW , end: END , name_end: := , sep: &end&
//! NEW /SITE-A
//!     Type:=  SITE &end& Owner:= /*
//!   NEW /PIPE-RACK-2
//!     ...
//!   END
//! END
//! ```
//!
//! The first line names the keywords; blocks nest like the RVM groups and are
//! matched to them by name. Each line is read as UTF-8 where it is, else as
//! Latin-1 ([`liftplan_core::names::utf8_or_latin1`]), as the RVM file's
//! names are, so that a name matches its group either way.

use crate::error::{PlantError, Result};
use liftplan_core::Location;
use std::collections::HashMap;
use std::path::Path;

/// Attributes by group name, in file order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Attributes {
    pub by_group: HashMap<String, Vec<(String, String)>>,
}

impl Attributes {
    pub fn get(&self, group: &str, key: &str) -> Option<&str> {
        self.by_group.get(group)?.iter().find(|(k, _)| k.eq_ignore_ascii_case(key)).map(|(_, v)| v.as_str())
    }
}

pub fn parse(path: &Path, bytes: &[u8]) -> Result<Attributes> {
    // Where a Windows tool saved the file with one.
    let bytes = liftplan_core::byte_order_mark::strip(bytes);
    // Line by line: a file may hold both (an E3D export's names with a
    // description typed elsewhere).
    let lines_read: Vec<std::borrow::Cow<str>> =
        bytes.split(|&b| b == b'\n').map(liftplan_core::names::utf8_or_latin1).collect();
    let text = lines_read.join("\n");
    let mut lines = text.lines().enumerate();
    let (_, first) = lines.next().ok_or_else(|| PlantError::at(Location::file(path), "the attribute file is empty"))?;
    if !first.starts_with("CADC_Attributes_File") {
        return Err(PlantError::at(
            Location::line(path, 1, Some(1)),
            "expected 'CADC_Attributes_File' on the first line",
        ));
    }
    let mut start = "NEW".to_string();
    let mut end = "END".to_string();
    let mut name_end = ":=".to_string();
    let mut sep = "&end&".to_string();
    for part in first.split(',') {
        if let Some((k, v)) = part.split_once(':') {
            let v = v.trim().to_string();
            match k.trim() {
                "start" if !v.is_empty() => start = v,
                "end" if !v.is_empty() => end = v,
                "name_end" if !v.is_empty() => name_end = v,
                "sep" if !v.is_empty() => sep = v,
                _ => {}
            }
        }
    }
    // Blocks by number, in the order their names first appear, so that a line
    // inside a block finds its list without hashing the block's name: a block
    // with a 2 MB name over 200,000 lines took 75 s when every line looked
    // its block up by name.
    let mut numbers: HashMap<String, usize> = HashMap::new();
    let mut groups: Vec<(String, Vec<(String, String)>)> = Vec::new();
    let mut stack: Vec<usize> = Vec::new();
    for (n, line) in lines {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        if let Some(rest) = t.strip_prefix(&start).filter(|r| r.is_empty() || r.starts_with(char::is_whitespace)) {
            let number = *numbers.entry(rest.trim().to_string()).or_insert_with_key(|name| {
                groups.push((name.clone(), Vec::new()));
                groups.len() - 1
            });
            stack.push(number);
            continue;
        }
        if t == end {
            if stack.pop().is_none() {
                return Err(PlantError::at(
                    Location::line(path, n as u64 + 1, Some(1)),
                    format!("'{end}' without a matching '{start}'"),
                ));
            }
            continue;
        }
        let Some(&group) = stack.last() else {
            return Err(PlantError::at(
                Location::line(path, n as u64 + 1, Some(1)),
                format!("attribute outside any '{start}' block"),
            ));
        };
        for item in t.split(sep.as_str()) {
            if let Some((k, v)) = item.split_once(name_end.as_str()) {
                groups[group].1.push((k.trim().to_string(), v.trim().to_string()));
            }
        }
    }
    if let Some(&open) = stack.last() {
        tracing::warn!("{}: block '{}' is not closed with '{end}'", path.display(), groups[open].0);
    }
    Ok(Attributes { by_group: groups.into_iter().collect() })
}

/// The attribute file beside an RVM file: the file of its name with the
/// extension `.att` in any case (`MODEL.ATT`), else `.txt` where it opens as
/// an attribute file (exports are delivered with their attributes renamed
/// so, to open in a text editor). `None` where there is neither.
pub fn beside(rvm: &Path) -> Option<std::path::PathBuf> {
    let dir = rvm.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let stem = rvm.file_stem()?;
    let mut candidates: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.file_stem() == Some(stem) && p.is_file())
        .collect();
    candidates.sort();
    let with = |ext: &'static str| {
        candidates
            .iter()
            .filter(move |p| p.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case(ext)))
    };
    let opens_as_attributes = |p: &&std::path::PathBuf| {
        let mut head = [0u8; 24];
        let n = std::fs::File::open(p).and_then(|mut f| std::io::Read::read(&mut f, &mut head)).unwrap_or(0);
        liftplan_core::byte_order_mark::strip(&head[..n]).starts_with(b"CADC_Attributes_File")
    };
    with("att").next().or_else(|| with("txt").find(opens_as_attributes)).cloned()
}

pub fn read(path: &Path) -> Result<Attributes> {
    let bytes = std::fs::read(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    parse(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The parser as first written, which looked each line's block up by
    /// name: the reference the numbered blocks must agree with.
    fn parse_by_name(text: &str) -> std::result::Result<Attributes, String> {
        let mut lines = text.lines().enumerate().skip(1);
        let mut out = Attributes::default();
        let mut stack: Vec<String> = Vec::new();
        for (n, line) in &mut lines {
            let t = line.trim();
            if t.is_empty() {
                continue;
            }
            if let Some(rest) = t.strip_prefix("NEW").filter(|r| r.is_empty() || r.starts_with(char::is_whitespace)) {
                out.by_group.entry(rest.trim().to_string()).or_default();
                stack.push(rest.trim().to_string());
            } else if t == "END" {
                stack.pop().ok_or(format!("line {}", n + 1))?;
            } else {
                let group = stack.last().ok_or(format!("line {}", n + 1))?;
                let list = out.by_group.entry(group.clone()).or_default();
                for item in t.split("&end&") {
                    if let Some((k, v)) = item.split_once(":=") {
                        list.push((k.trim().to_string(), v.trim().to_string()));
                    }
                }
            }
        }
        Ok(out)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]
        /// Random files of nested, repeated and unclosed blocks (names
        /// reused, one nested in itself), attributes in and outside them.
        #[test]
        fn numbered_blocks_read_as_blocks_by_name(
            lines in proptest::collection::vec(prop_oneof![
                3 => (0u8..3).prop_map(|k| format!("NEW /G{k}")),
                2 => Just("END".to_string()),
                4 => (0u8..4, 0u8..9).prop_map(|(k, v)| format!("  K{k}:= {v} &end& K{}:=x", k + 1)),
                1 => Just(String::new()),
            ], 0..40)
        ) {
            let text = format!("CADC_Attributes_File v1.0 , start: NEW , end: END\n{}\n", lines.join("\n"));
            let numbered = parse(Path::new("r.att"), text.as_bytes()).map_err(|e| e.to_string());
            match parse_by_name(&text) {
                Ok(by_name) => prop_assert_eq!(numbered, Ok(by_name)),
                Err(at) => prop_assert!(numbered.as_ref().is_err_and(|e| e.contains(&format!("r.att:{}:", &at[5..]))), "{:?}", numbered),
            }
        }
    }

    #[test]
    fn nested_blocks_and_separators() {
        let t = b"CADC_Attributes_File v1.0 , start: NEW , end: END , name_end: := , sep: &end&\nNEW /A\n Type:= SITE &end& Owner:= /*\n NEW /B\n  Type:= ZONE\n END\nEND\n";
        let a = parse(Path::new("x.att"), t).unwrap();
        assert_eq!(a.get("/A", "type"), Some("SITE"));
        assert_eq!(a.get("/A", "Owner"), Some("/*"));
        assert_eq!(a.get("/B", "Type"), Some("ZONE"));
        let e = parse(Path::new("x.att"), b"CADC_Attributes_File v1.0\nEND\n").unwrap_err();
        assert!(e.to_string().contains("x.att:2:1"), "{e}");
    }

    /// A file saved with a UTF-8 byte order mark (it was refused for not
    /// starting with `CADC_Attributes_File`) reads as without it.
    #[test]
    fn a_byte_order_mark_is_passed_over() {
        let t = b"\xef\xbb\xbfCADC_Attributes_File v1.0 , start: NEW , end: END\nNEW /A\n Type:= SITE\nEND\n";
        let a = parse(Path::new("x.att"), t).unwrap();
        assert_eq!(a.get("/A", "Type"), Some("SITE"));
    }

    /// A line in UTF-8 (as AVEVA E3D writes) reads as UTF-8, one in Latin-1
    /// (as PDMS wrote) as Latin-1, in the same file, as the RVM file's names
    /// are read: a UTF-8 "/BEHÄLTER" read as "/BEHÃ\u{84}LTER" before, on the
    /// plan's pages too.
    #[test]
    fn lines_in_utf8_or_latin1_read_as_their_text() {
        let t = b"CADC_Attributes_File v1.0 , start: NEW , end: END\nNEW /BEH\xc3\x84LTER\n Description:= Beh\xe4lter \xd8 2 m\nEND\nNEW /STRA\xdfE\nEND\n";
        let a = parse(Path::new("x.att"), t).unwrap();
        assert_eq!(a.get("/BEHÄLTER", "Description"), Some("Behälter Ø 2 m"));
        assert!(a.by_group.contains_key("/STRAßE"));
    }
}
