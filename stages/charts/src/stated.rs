//! What a chart sheet states in words beside a grid: the permissible wind
//! speed ("Permissible wind speed 9.8 m/s", "zul. Windgeschwindigkeit
//! 35 km/h") and the counterweight rigged ("Counterweight 140 t, outrigger
//! base 11.5 x 11.5 m"), each with the cell it is in.
//!
//! It reads, it does not decide: where a sheet states two different speeds
//! (a reduced one for long booms, say) both are kept, and the stages that
//! use them say which they took or that they took none.

use crate::sheet::{Sheet, Val};
use liftplan_core::capacity::StatedOnChart;
use liftplan_core::location::cell_ref;

/// The wind speeds (m/s) a text states: a number followed by m/s, km/h or
/// mph, in a text that speaks of wind.
pub fn wind_speeds_ms(text: &str) -> Vec<f64> {
    let lower = text.to_lowercase();
    if !lower.contains("wind") {
        return Vec::new();
    }
    let b = lower.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        // A number starts at a digit that does not continue a word or a number.
        if !b[i].is_ascii_digit() || (i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'.')) {
            i += 1;
            continue;
        }
        let start = i;
        while i < b.len()
            && (b[i].is_ascii_digit()
                || ((b[i] == b'.' || b[i] == b',') && i + 1 < b.len() && b[i + 1].is_ascii_digit()))
        {
            i += 1;
        }
        let Ok(v) = lower[start..i].replace(',', ".").parse::<f64>() else { continue };
        let after = lower[i..].trim_start();
        let per_s = [("m/s", 1.0), ("km/h", 1.0 / 3.6), ("kmh", 1.0 / 3.6), ("mph", 0.447_04)]
            .into_iter()
            .find(|(unit, _)| after.starts_with(unit) && !after[unit.len()..].starts_with(char::is_alphanumeric));
        if let Some((_, f)) = per_s {
            let ms = v * f;
            if ms.is_finite() && ms > 0.0 && ms <= liftplan_core::wind::MAX_CHART_WIND_MS {
                out.push(ms);
            }
        }
    }
    out
}

/// What the text cells of `sheet` in `rows` and `cols` (inclusive) state,
/// each value once (the first cell stating it), in the sheet's order.
pub struct Stated {
    pub wind_ms: Vec<StatedOnChart>,
    pub counterweight_kg: Vec<StatedOnChart>,
}

/// Adds `stated` to `into` unless a value the same (to a millionth) is
/// there already: each value once, the first cell stating it.
pub fn keep_once(into: &mut Vec<StatedOnChart>, stated: StatedOnChart) {
    if !into.iter().any(|s| (s.value - stated.value).abs() <= 1e-6 * stated.value.abs().max(1.0)) {
        into.push(stated);
    }
}

/// Reads [`Stated`] from the text cells of `sheet` in `rows` and `cols`.
pub fn on_sheet(sheet: &Sheet, rows: std::ops::RangeInclusive<u32>, cols: std::ops::RangeInclusive<u32>) -> Stated {
    let mut stated = Stated { wind_ms: Vec::new(), counterweight_kg: Vec::new() };
    let keep = |into: &mut Vec<StatedOnChart>, value: f64, r: u32, c: u32, text: &str| {
        keep_once(
            into,
            StatedOnChart { value, cell: format!("{}!{}", sheet.name, cell_ref(r, c)), text: text.to_string() },
        )
    };
    // Side by side, a grid's rows may lie above the grid before it ends.
    if rows.is_empty() {
        return stated;
    }
    for (&(r, c), v) in sheet.cells.range((*rows.start(), 0)..=(*rows.end(), u32::MAX)) {
        let Val::Text(text) = v else { continue };
        if !cols.contains(&c) {
            continue;
        }
        for ms in wind_speeds_ms(text) {
            keep(&mut stated.wind_ms, ms, r, c, text);
        }
        if let Some(kg) = liftplan_core::lift::counterweight_named_kg(text) {
            keep(&mut stated.counterweight_kg, kg, r, c, text);
        }
    }
    stated
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wind_speeds_are_read_in_their_units() {
        assert_eq!(wind_speeds_ms("Permissible wind speed 9.8 m/s (3 s gust)"), vec![9.8]);
        assert_eq!(wind_speeds_ms("zul. Windgeschwindigkeit 9,8 m/s"), vec![9.8]);
        let kmh = wind_speeds_ms("Max. wind speed: 36 km/h");
        assert!(kmh.len() == 1 && (kmh[0] - 10.0).abs() < 1e-12, "{kmh:?}");
        assert!((wind_speeds_ms("wind 20 mph")[0] - 8.9408).abs() < 1e-12);
        // No wind spoken of, no unit, a number inside a word: nothing.
        assert!(wind_speeds_ms("Counterweight 9.8 m/s").is_empty());
        assert!(wind_speeds_ms("wind zone 3").is_empty());
        assert!(wind_speeds_ms("wind class B2 m/s").is_empty());
        assert_eq!(wind_speeds_ms("wind 9.8 m/s; over 60 m boom 7.0 m/s"), vec![9.8, 7.0]);
    }

    #[test]
    fn a_sheet_states_each_value_once_with_its_cell() {
        let mut sheet = Sheet { name: "Main".into(), ..Default::default() };
        sheet.cells.insert((2, 0), Val::Text("Counterweight 140 t, outrigger base 11.5 x 11.5 m".into()));
        sheet.cells.insert((40, 0), Val::Text("4) Permissible wind speed 9.8 m/s.".into()));
        sheet.cells.insert((41, 3), Val::Text("wind: 9.8 m/s".into()));
        sheet.cells.insert((50, 0), Val::Text("wind 12 m/s".into()));
        let s = on_sheet(&sheet, 0..=45, 0..=u32::MAX);
        assert_eq!(s.wind_ms.len(), 1);
        assert_eq!((s.wind_ms[0].value, s.wind_ms[0].cell.as_str()), (9.8, "Main!A41"));
        assert_eq!((s.counterweight_kg[0].value, s.counterweight_kg[0].cell.as_str()), (140_000.0, "Main!A3"));
        assert_eq!(on_sheet(&sheet, 0..=60, 0..=u32::MAX).wind_ms.len(), 2);
        #[allow(clippy::reversed_empty_ranges)]
        let none = on_sheet(&sheet, 9..=3, 0..=u32::MAX);
        assert!(none.wind_ms.is_empty() && none.counterweight_kg.is_empty());
    }
}
