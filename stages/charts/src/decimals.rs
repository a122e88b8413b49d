//! Numbers written as text in a chart's cells, and how they mark their
//! decimals.
//!
//! Charts pasted from a PDF, or typed into an Excel set to another locale,
//! hold their numbers as text: "12.5", "12,5", "1,250.5", "1.250,5". Read
//! one cell at a time, "12,500" is twelve and a half tonnes in Germany and
//! twelve thousand five hundred pounds in the United States. A grid writes
//! its numbers one way, so the way is decided from the cells of the grid
//! that show it ([`shown_by`]) and held for the whole grid ([`GridMark`]):
//! a number that shows no mark of its own ("12,500") is read with it. Where
//! the grid's numbers show both marks, such a number is refused; where they
//! show neither, it is read the common way (the comma separating
//! thousands, the point marking decimals) and the reading is reported
//! ([`Reading::Guessed`]), never taken silently.
//!
//! This module reads digits and separators only: blanks, units and
//! footnote marks are the caller's to take off first, and what a unit
//! tells (no capacity in kg or lb has three decimal places) the caller's to
//! apply.

/// How a grid's numbers written as text mark their decimals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DecimalMark {
    /// "1,250.5": a point marks decimals, commas separate thousands.
    Point,
    /// "1.250,5": a comma marks decimals, points separate thousands.
    Comma,
}

impl DecimalMark {
    fn separator(self) -> char {
        match self {
            DecimalMark::Point => '.',
            DecimalMark::Comma => ',',
        }
    }

    fn thousands(self) -> char {
        match self {
            DecimalMark::Point => ',',
            DecimalMark::Comma => '.',
        }
    }
}

/// How a number was read, for the grid's warnings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reading {
    /// Digits, or a point marking decimals in a grid written that way (or
    /// showing no way): nothing to say.
    Plain,
    /// A comma marking decimals.
    DecimalComma,
    /// One separator followed by exactly three digits ("12,500", "12.500")
    /// in a grid whose numbers show no decimal mark: read the common way.
    Guessed,
}

/// What a number written as text (digits, points and commas only) shows of
/// its decimal mark: `None` where it shows none, as plain digits do and as
/// one separator followed by exactly three digits does.
pub fn shown_by(number: &str) -> Option<DecimalMark> {
    let (commas, points) = (number.matches(',').count(), number.matches('.').count());
    match (commas, points) {
        (0, 0) => None,
        (_, 0) if commas > 1 => Some(DecimalMark::Point),
        (0, _) if points > 1 => Some(DecimalMark::Comma),
        (1, 0) | (0, 1) => {
            let after = number.len() - number.find([',', '.']).map_or(number.len(), |i| i + 1);
            match (after == 3, commas == 1) {
                (true, _) => None,
                (false, true) => Some(DecimalMark::Comma),
                (false, false) => Some(DecimalMark::Point),
            }
        }
        // Both: the later one marks the decimals.
        _ => {
            let last_comma = number.rfind(',');
            let last_point = number.rfind('.');
            if last_comma > last_point { Some(DecimalMark::Comma) } else { Some(DecimalMark::Point) }
        }
    }
}

/// A number written as text (digits, points and commas only), read with
/// its own decimal mark where it shows one, else the grid's (`None`: the
/// grid shows none; see [`GridMark::for_number`]). `None` where the text is
/// not a number: a separator at either end, a decimal mark twice, thousands
/// groups not of three digits.
pub fn read(number: &str, grid: Option<DecimalMark>) -> Option<(f64, Reading)> {
    if !number.starts_with(|c: char| c.is_ascii_digit()) || !number.ends_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    if !number.bytes().all(|b| b.is_ascii_digit() || b == b',' || b == b'.') {
        return None;
    }
    let shown = shown_by(number);
    let (mark, guessed) = match (shown, grid) {
        (Some(m), _) | (None, Some(m)) => (m, false),
        (None, None) => (DecimalMark::Point, number.contains([',', '.'])),
    };
    let (whole, fraction) = match number.split_once(mark.separator()) {
        Some((w, f)) => (w, Some(f)),
        None => (number, None),
    };
    if fraction.is_some_and(|f| f.contains(mark.separator()) || f.contains(mark.thousands())) {
        return None;
    }
    let mut groups = whole.split(mark.thousands());
    let first = groups.next().unwrap_or_default();
    if first.is_empty() || groups.clone().any(|g| g.len() != 3) || (whole.contains(mark.thousands()) && first.len() > 3)
    {
        return None;
    }
    let digits: String = whole.chars().filter(char::is_ascii_digit).collect();
    let value: f64 = match fraction {
        Some(f) => format!("{digits}.{f}").parse().ok()?,
        None => digits.parse().ok()?,
    };
    let reading = if guessed {
        Reading::Guessed
    } else if mark == DecimalMark::Comma && fraction.is_some() {
        Reading::DecimalComma
    } else {
        Reading::Plain
    };
    value.is_finite().then_some((value, reading))
}

/// The decimal mark a grid's numbers written as text show.
#[derive(Debug, Clone, PartialEq)]
pub enum GridMark {
    /// None shows one.
    Neither,
    One(DecimalMark),
    /// Some show each: the first cell of each and its number.
    Both {
        comma: (String, String),
        point: (String, String),
    },
}

impl GridMark {
    /// The grid's mark, from each number written as text and the cell it
    /// is in, in the grid's order.
    pub fn of(numbers: impl IntoIterator<Item = (String, String)>) -> GridMark {
        let (mut comma, mut point) = (None, None);
        for (cell, number) in numbers {
            let first = match shown_by(&number) {
                Some(DecimalMark::Comma) => &mut comma,
                Some(DecimalMark::Point) => &mut point,
                None => continue,
            };
            if first.is_none() {
                *first = Some((cell, number));
            }
            if comma.is_some() && point.is_some() {
                break;
            }
        }
        match (comma, point) {
            (None, None) => GridMark::Neither,
            (Some(_), None) => GridMark::One(DecimalMark::Comma),
            (None, Some(_)) => GridMark::One(DecimalMark::Point),
            (Some(comma), Some(point)) => GridMark::Both { comma, point },
        }
    }

    /// The mark to read `number` with ([`read`]): its own where it shows
    /// one, else the grid's (`None` where the grid shows none). A number
    /// that shows none but has a separator ("12,500") is refused in a grid
    /// that shows both: it may be read either way.
    pub fn for_number(&self, number: &str) -> Result<Option<DecimalMark>, String> {
        if let Some(own) = shown_by(number) {
            return Ok(Some(own));
        }
        match self {
            GridMark::Neither => Ok(None),
            GridMark::One(m) => Ok(Some(*m)),
            GridMark::Both { .. } if !number.contains([',', '.']) => Ok(None),
            GridMark::Both { comma, point } => {
                let (Some((comma_read, _)), Some((point_read, _))) =
                    (read(number, Some(DecimalMark::Comma)), read(number, Some(DecimalMark::Point)))
                else {
                    return Ok(None);
                };
                Err(format!(
                    "'{number}' may be {comma_read} or {point_read}, and the grid writes decimals with a comma \
                     ({} '{}') and with a point ({} '{}'), so which is meant cannot be told: correct the cell (or \
                     type the numbers in as numbers)",
                    comma.0, comma.1, point.0, point.1
                ))
            }
        }
    }
}

/// A plain number written alone in a cell, as radii and boom lengths are:
/// digits with at most one separator, read as a decimal mark, and blanks
/// around it. One separator followed by exactly three digits ("1,000") is
/// not read, as it may separate thousands: the cell stays text, and the grid
/// is refused or described rather than read one of two ways. The mark comes
/// with the value where it was a comma.
pub fn plain_number(text: &str) -> Option<(f64, Reading)> {
    let t = text.trim_matches(|c: char| c.is_whitespace() || c == '\u{a0}');
    if t.matches([',', '.']).count() > 1 {
        return None;
    }
    match read(t, None)? {
        (_, Reading::Guessed) => None,
        read => Some(read),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use DecimalMark::{Comma, Point};

    #[test]
    fn what_a_number_shows() {
        for (n, shows) in [
            ("125", None),
            ("12,5", Some(Comma)),
            ("12.5", Some(Point)),
            ("12,500", None),
            ("12.500", None),
            ("1,250.5", Some(Point)),
            ("1.250,5", Some(Comma)),
            ("1,250,000", Some(Point)),
            ("1.250.000", Some(Comma)),
            ("0,25", Some(Comma)),
            ("12,5000", Some(Comma)),
        ] {
            assert_eq!(shown_by(n), shows, "{n}");
        }
    }

    #[test]
    fn numbers_are_read_with_the_grids_mark() {
        let cases: [(&str, Option<DecimalMark>, Option<(f64, Reading)>); 16] = [
            ("125", None, Some((125.0, Reading::Plain))),
            ("12.5", None, Some((12.5, Reading::Plain))),
            ("12,5", None, Some((12.5, Reading::DecimalComma))),
            ("12,500", None, Some((12500.0, Reading::Guessed))),
            ("12.500", None, Some((12.5, Reading::Guessed))),
            ("12,500", Some(Comma), Some((12.5, Reading::DecimalComma))),
            ("12.500", Some(Comma), Some((12500.0, Reading::Plain))),
            ("12,500", Some(Point), Some((12500.0, Reading::Plain))),
            ("1.250,5", None, Some((1250.5, Reading::DecimalComma))),
            ("1,250.5", Some(Point), Some((1250.5, Reading::Plain))),
            ("1,250,000", None, Some((1_250_000.0, Reading::Plain))),
            // Shows the other mark than its grid's: read by its own.
            ("12,5", Some(Point), Some((12.5, Reading::DecimalComma))),
            // Thousands groups not of three digits, a separator at an end,
            // a decimal mark twice, something else.
            ("1,25,000", Some(Point), None),
            ("12,", None, None),
            (",5", None, None),
            ("1.2e3", None, None),
        ];
        for (n, grid, expected) in cases {
            assert_eq!(read(n, grid), expected, "{n} {grid:?}");
        }
        assert_eq!(read("1.250.000,5", None), Some((1_250_000.5, Reading::DecimalComma)));
        assert_eq!(read("1,250,000.5,5", None), None);
    }

    #[test]
    fn a_grids_mark_reads_the_numbers_that_show_none() {
        let grid = |ns: &[&'static str]| {
            GridMark::of(ns.iter().enumerate().map(|(i, n)| (format!("B{}", i + 1), n.to_string())))
        };
        assert_eq!(grid(&["125", "12,500", "12,5"]), GridMark::One(Comma));
        assert_eq!(grid(&["125", "12,500"]), GridMark::Neither);
        let both = grid(&["12,5", "12", "8.4", "12,500"]);
        assert_eq!(both, GridMark::Both { comma: ("B1".into(), "12,5".into()), point: ("B3".into(), "8.4".into()) });
        // Each number that shows its mark is read by it; one that shows
        // none is read with the grid's, and refused where the grid shows
        // both.
        assert_eq!(both.for_number("8.4"), Ok(Some(Point)));
        assert_eq!(both.for_number("75,5"), Ok(Some(Comma)));
        assert_eq!(both.for_number("125"), Ok(None));
        let why = both.for_number("12,500").unwrap_err();
        assert!(why.starts_with("'12,500' may be 12.5 or 12500, and the grid writes decimals with a comma (B1 '12,5') and with a point (B3 '8.4')"), "{why}");
        assert_eq!(grid(&["12,5"]).for_number("12,500"), Ok(Some(Comma)));
        assert_eq!(GridMark::Neither.for_number("12,500"), Ok(None));
    }

    /// A number written either way, with or without thousands separators,
    /// reads back as itself with its grid's mark; where it shows its own
    /// mark, with no grid's mark as well.
    mod written_either_way {
        use super::*;
        use proptest::prelude::*;

        fn written(whole: u64, fraction: &str, mark: DecimalMark, grouped: bool) -> String {
            let digits = whole.to_string();
            let mut out = String::new();
            for (i, d) in digits.chars().enumerate() {
                if grouped && i > 0 && (digits.len() - i).is_multiple_of(3) {
                    out.push(mark.thousands());
                }
                out.push(d);
            }
            if !fraction.is_empty() {
                out.push(mark.separator());
                out.push_str(fraction);
            }
            out
        }

        proptest! {
            #[test]
            fn reads_back(whole in 0u64..10_000_000, fraction in "[0-9]{0,4}", comma: bool, grouped: bool) {
                let mark = if comma { Comma } else { Point };
                let text = written(whole, &fraction, mark, grouped);
                let value: f64 = format!("{whole}.{fraction}0").parse().unwrap();
                let (read_back, _) = read(&text, Some(mark)).unwrap();
                prop_assert_eq!(read_back, value, "{}", text);
                if let Some(shown) = shown_by(&text) {
                    prop_assert_eq!(shown, mark, "{}", text);
                    prop_assert_eq!(read(&text, None).map(|r| r.0), Some(value), "{}", text);
                }
            }
        }
    }

    #[test]
    fn plain_numbers_alone_in_a_cell() {
        assert_eq!(plain_number(" 12,5\u{a0}"), Some((12.5, Reading::DecimalComma)));
        assert_eq!(plain_number("16"), Some((16.0, Reading::Plain)));
        assert_eq!(plain_number("37.5"), Some((37.5, Reading::Plain)));
        for not in ["1,000", "1.000", "1,250.5", "12 m", "", "-3", "3e2", "Radius"] {
            assert_eq!(plain_number(not), None, "{not}");
        }
    }
}
