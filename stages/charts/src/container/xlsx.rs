//! An xlsx workbook's shared strings table (`xl/sharedStrings.xml`),
//! checked before calamine reads it: the number of strings it says it holds
//! must be one it could hold (see [the container module](super)); and its
//! workbook part (`xl/workbook.xml`), for whether it asks to be recalculated
//! when opened.

use crate::sheet::MAX_CELLS;
use quick_xml::events::Event;

/// Whether a zip part is a shared strings table. calamine reads the one in
/// the workbook's folder; every part of that name counts here, in any case.
pub(super) fn is_shared_strings(name: &str) -> bool {
    name.rsplit('/').next().is_some_and(|file| file.eq_ignore_ascii_case("sharedStrings.xml"))
}

/// What calamine would make of a shared strings table: `Err(())` if the part
/// cannot be read (calamine reports it), `Ok(Err(message))` if it must not be
/// given to calamine.
///
/// calamine reserves room for as many strings as the table's `uniqueCount`
/// attribute says before it reads one: a 20 kB workbook saying ten billion
/// asked for 240 GB, and liftplan aborted. A count is refused when it is over
/// both the table's own `<si>` elements and [`MAX_CELLS`] (room for that many
/// is 48 MB, and a load chart has no more cells). Every `sst` element's count
/// is read, whatever its prefix; XML that stops being well-formed ends the
/// walk with the elements counted so far (calamine reserves before it reads
/// them).
pub(super) fn check_shared_strings(
    xml: &mut impl std::io::BufRead,
) -> std::result::Result<std::result::Result<(), String>, ()> {
    let mut reader = quick_xml::Reader::from_reader(xml);
    let mut buf = Vec::new();
    let (mut claimed, mut strings) = (0u64, 0u64);
    loop {
        match reader.read_event_into(&mut buf) {
            Ok(Event::Start(e) | Event::Empty(e)) => match e.local_name().into_inner() {
                "sst" => {
                    for a in e.attributes().flatten() {
                        if a.key.local_name().into_inner() == "uniqueCount" {
                            claimed = claimed.max(count(a.value.as_bytes()).unwrap_or(0));
                        }
                    }
                }
                "si" => strings += 1,
                _ => {}
            },
            Ok(Event::Eof) => break,
            Ok(_) => {}
            Err(quick_xml::Error::Io(_)) => return Err(()),
            Err(_) => break,
        }
        buf.clear();
    }
    if claimed > strings.max(MAX_CELLS as u64) {
        return Ok(Err(format!(
            "its shared strings table says it holds {claimed} strings (uniqueCount) but holds {strings}; the \
             workbook is damaged"
        )));
    }
    Ok(Ok(()))
}

/// Whether a part is the workbook part calamine reads (`xl/workbook.xml`).
pub(super) fn is_workbook(name: &str) -> bool {
    name.eq_ignore_ascii_case("xl/workbook.xml")
}

/// Whether the workbook part asks for every formula to be calculated again
/// when the workbook is opened (`<calcPr fullCalcOnLoad="1"/>`): programs
/// that write workbooks without calculating them (XlsxWriter,
/// rust_xlsxwriter, openpyxl) ask so and store 0, or nothing, as each
/// formula's value; Excel, saving a workbook, does not. `Err(())` where the
/// part cannot be read.
pub(super) fn asks_full_calculation_on_open(xml: &mut impl std::io::BufRead) -> std::result::Result<bool, ()> {
    let mut reader = quick_xml::Reader::from_reader(xml);
    let mut buf = Vec::new();
    loop {
        match reader.read_event_into(&mut buf) {
            Ok(Event::Start(e) | Event::Empty(e)) if e.local_name().into_inner() == "calcPr" => {
                return Ok(e.attributes().flatten().any(|a| {
                    a.key.local_name().into_inner() == "fullCalcOnLoad" && matches!(a.value.as_ref(), "1" | "true")
                }));
            }
            Ok(Event::Eof) => return Ok(false),
            Ok(_) => {}
            Err(quick_xml::Error::Io(_)) => return Err(()),
            Err(_) => return Ok(false),
        }
        buf.clear();
    }
}

/// A count as calamine reads one: decimal digits only (leading zeros
/// allowed), within `usize`; `None` for anything else, which calamine
/// ignores.
fn count(raw: &[u8]) -> Option<u64> {
    if raw.is_empty() || !raw.iter().all(u8::is_ascii_digit) {
        return None;
    }
    raw.iter().try_fold(0u64, |n, d| n.checked_mul(10)?.checked_add((d - b'0') as u64))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn verdict(xml: &str) -> std::result::Result<(), String> {
        check_shared_strings(&mut xml.as_bytes()).unwrap()
    }

    #[test]
    fn a_count_over_what_the_table_holds_is_refused() {
        let table = |count: &str, items: usize| {
            format!(
                "<?xml version=\"1.0\"?><sst xmlns=\"x\" count=\"3\" uniqueCount=\"{count}\">{}</sst>",
                "<si><t>Radius (m)</t></si>".repeat(items)
            )
        };
        assert_eq!(verdict(&table("3", 3)), Ok(()));
        // A wrong count that cannot hurt (48 MB at most) is left to calamine.
        assert_eq!(verdict(&table("2000000", 3)), Ok(()));
        assert_eq!(verdict(&table("abc", 1)), Ok(()));
        let e = verdict(&table("10000000000", 3)).unwrap_err();
        assert!(e.contains("says it holds 10000000000 strings (uniqueCount) but holds 3"), "{e}");
        // Leading zeros, a prefix, an element cut short after the count: all
        // read as calamine would reserve for them.
        assert!(verdict(&table("0002000001", 0)).is_err());
        assert!(verdict("<x:sst xmlns:x=\"x\" uniqueCount=\"2000001\"><x:si/></x:sst>").is_err());
        assert!(verdict("<sst uniqueCount=\"2000001\"><si><t>cut short").is_err());
        // Counts past u64 are not numbers to calamine either.
        assert_eq!(verdict(&table("99999999999999999999999", 1)), Ok(()));
    }

    #[test]
    fn a_workbook_asking_to_be_calculated_on_open_is_told() {
        let asks = |xml: &str| asks_full_calculation_on_open(&mut xml.as_bytes()).unwrap();
        assert!(asks(r#"<workbook><sheets/><calcPr calcId="124519" fullCalcOnLoad="1"/></workbook>"#));
        assert!(asks(r#"<x:workbook xmlns:x="s"><x:calcPr fullCalcOnLoad="true"></x:calcPr></x:workbook>"#));
        assert!(!asks(r#"<workbook><calcPr calcId="191029"/></workbook>"#));
        assert!(!asks(r#"<workbook><sheets/></workbook>"#));
        assert!(!asks("<workbook><calcPr fullCalcOnLoad="));
    }

    #[test]
    fn shared_strings_parts_are_found_by_name() {
        assert!(is_shared_strings("xl/sharedStrings.xml"));
        assert!(is_shared_strings("XL/SHAREDSTRINGS.XML"));
        assert!(is_shared_strings("sharedStrings.xml"));
        assert!(!is_shared_strings("xl/worksheets/sheet1.xml"));
    }
}
