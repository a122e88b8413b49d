//! Load charts in real workbook files: layouts, units, typos, refusals.

use liftplan_charts::{Settings, TableMapping, read_chart};
use liftplan_core::units::{KG_PER_LB, M_PER_FT};
use rust_xlsxwriter::Workbook;
use std::path::Path;

#[test]
fn demo_chart_has_two_configurations_with_cells() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("ac700.xlsx");
    liftplan_fixtures::chart::write_demo_chart(&p).unwrap();
    let (configs, reports) = read_chart(&p, &Settings::default()).unwrap();
    assert_eq!(configs.len(), 2);
    assert_eq!(configs[0].name, "Main boom 360");
    assert_eq!(configs[0].boom_lengths_m, liftplan_fixtures::chart::DEMO_BOOMS_M.to_vec());
    assert_eq!(configs[0].radii_m, liftplan_fixtures::chart::demo_radii_m());
    assert!(reports[0].warnings.is_empty(), "{:?}", reports[0].warnings);
    assert_eq!(reports[0].units.found, vec!["capacity in t", "radius in m"]);
    // Between boom lengths and radii: the next longer boom and next larger radius.
    let c = configs[0].lookup(40.0, 29.0).unwrap();
    let want = liftplan_fixtures::chart::demo_capacity_t(30.0, 41.8, 1.0).unwrap();
    assert!((c.capacity_kg - want * 1000.0).abs() < 1e-6, "{c:?} vs {want}");
    assert_eq!((c.boom_m, c.radius_m), (41.8, 30.0));
    assert!(c.cell.starts_with("ac700.xlsx [Main boom 360!"), "{}", c.cell);
    // Beyond the last row: not permitted.
    assert!(configs[0].lookup(40.0, 57.0).is_err());
}

/// The same physical chart in feet and pounds.
fn write_grid(
    path: &Path,
    header: &str,
    radius_label: &str,
    booms: &[f64],
    radii: &[f64],
    value: impl Fn(f64, f64) -> Option<String>,
    transposed: bool,
) {
    let mut wb = Workbook::new();
    let ws = wb.add_worksheet().set_name("Chart").unwrap();
    ws.write_string(0, 0, header).unwrap();
    if transposed {
        ws.write_string(2, 0, "Boom length").unwrap();
        ws.write_string(2, 1, radius_label).unwrap();
        for (j, r) in radii.iter().enumerate() {
            ws.write_number(3, 1 + j as u16, *r).unwrap();
        }
        for (i, b) in booms.iter().enumerate() {
            ws.write_number(4 + i as u32, 0, *b).unwrap();
            for (j, r) in radii.iter().enumerate() {
                match value(*r, *b) {
                    Some(v) => ws.write_string(4 + i as u32, 1 + j as u16, v).unwrap(),
                    None => ws.write_string(4 + i as u32, 1 + j as u16, "-").unwrap(),
                };
            }
        }
    } else {
        ws.write_string(2, 0, radius_label).unwrap();
        ws.write_string(2, 1, "Boom length").unwrap();
        for (j, b) in booms.iter().enumerate() {
            ws.write_number(3, 1 + j as u16, *b).unwrap();
        }
        for (i, r) in radii.iter().enumerate() {
            ws.write_number(4 + i as u32, 0, *r).unwrap();
            for (j, b) in booms.iter().enumerate() {
                match value(*r, *b) {
                    Some(v) => ws.write_string(4 + i as u32, 1 + j as u16, v).unwrap(),
                    None => ws.write_string(4 + i as u32, 1 + j as u16, "").unwrap(),
                };
            }
        }
    }
    wb.save(path).unwrap();
}

/// The small chart most tests here write: in t and m, booms 20 and 30 m
/// across, radii 4, 6 and 10 m down, each capacity as `value` writes it.
fn write_metric_grid(path: &Path, value: impl Fn(f64, f64) -> Option<String>) {
    write_grid(path, "Capacities in t", "Radius (m)", &[20.0, 30.0], &[4.0, 6.0, 10.0], value, false);
}

fn cap_t(r_m: f64, b_m: f64) -> Option<f64> {
    (r_m < b_m - 2.0).then(|| 400.0 / (r_m + 2.0) * (30.0 / b_m))
}

#[test]
fn feet_and_pounds_give_the_same_table() {
    let d = tempfile::tempdir().unwrap();
    let booms_m = [20.0, 30.0, 40.0];
    let radii_m = [4.0, 6.0, 10.0, 16.0, 24.0];
    let metric = d.path().join("metric.xlsx");
    write_grid(
        &metric,
        "Capacities in t",
        "Radius (m)",
        &booms_m,
        &radii_m,
        |r, b| cap_t(r, b).map(|c| format!("{c}")),
        false,
    );
    let imperial = d.path().join("imperial.xlsx");
    let booms_ft: Vec<f64> = booms_m.iter().map(|b| b / M_PER_FT).collect();
    let radii_ft: Vec<f64> = radii_m.iter().map(|r| r / M_PER_FT).collect();
    write_grid(
        &imperial,
        "Capacities in lbs",
        "Radius (ft)",
        &booms_ft,
        &radii_ft,
        |r, b| cap_t(r * M_PER_FT, b * M_PER_FT).map(|c| format!("{}", c * 1000.0 / KG_PER_LB)),
        false,
    );
    let (m, _) = read_chart(&metric, &Settings::default()).unwrap();
    let (i, rep) = read_chart(&imperial, &Settings::default()).unwrap();
    assert_eq!(rep[0].units.found, vec!["capacity in lb", "radius in ft"]);
    assert_eq!(m[0].radii_m.len(), i[0].radii_m.len());
    for (a, b) in m[0].radii_m.iter().zip(&i[0].radii_m) {
        assert!((a - b).abs() < 1e-9);
    }
    for (a, b) in m[0].cells.iter().zip(&i[0].cells) {
        match (a, b) {
            (Some(a), Some(b)) => assert!(
                (a.capacity_kg - b.capacity_kg).abs() < 1e-6 * a.capacity_kg,
                "{} vs {}",
                a.capacity_kg,
                b.capacity_kg
            ),
            (None, None) => {}
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn transposed_layout_is_recognised() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("t.xlsx");
    write_grid(
        &p,
        "Capacities in t",
        "Radius (m)",
        &[20.0, 30.0],
        &[4.0, 6.0, 10.0],
        |r, b| cap_t(r, b).map(|c| format!("{c}")),
        true,
    );
    let (c, rep) = read_chart(&p, &Settings::default()).unwrap();
    assert!(rep[0].transposed);
    assert_eq!(c[0].boom_lengths_m, vec![20.0, 30.0]);
    assert_eq!(c[0].radii_m, vec![4.0, 6.0, 10.0]);
    assert!((c[0].lookup(30.0, 5.0).unwrap().capacity_kg - cap_t(6.0, 30.0).unwrap() * 1000.0).abs() < 1e-6);
}

/// The demo chart with every number written as text, as a chart pasted
/// from a PDF or typed into an Excel set to another locale holds them:
/// radii, boom lengths and capacities, with decimal points and with decimal
/// commas, capacities to three decimals ("482,600": read alone, twelve
/// thousand or twelve; the grid's "3,5" m radius says which). Each reads as
/// the chart of numbers does; decimal commas are said once a grid. Radii
/// and boom lengths pasted with their unit in the cell ("3,5 m") read as
/// well.
#[test]
fn numbers_written_as_text_read_as_the_numbers() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("ac700.xlsx");
    liftplan_fixtures::chart::write_demo_chart(&p).unwrap();
    let (numbers, _) = read_chart(&p, &Settings::default()).unwrap();
    let sheets = liftplan_charts::sheet::read_workbook(&p).unwrap();
    for (mark, capacities, unit_in_axis) in [
        ('.', false, false),
        ('.', true, false),
        (',', false, false),
        (',', true, false),
        ('.', false, true),
        (',', true, true),
    ] {
        let mut wb = Workbook::new();
        for sheet in &sheets {
            let ws = wb.add_worksheet().set_name(&sheet.name).unwrap();
            for (&(r, c), v) in &sheet.cells {
                let text = match v {
                    // Booms and radii are in the first column and row 5
                    // (0-based): capacities below and right of them.
                    liftplan_charts::sheet::Val::Num(x) if capacities && r > 5 && c > 0 => format!("{x:.3}"),
                    liftplan_charts::sheet::Val::Num(x) => format!("{x}"),
                    liftplan_charts::sheet::Val::Text(t) => t.clone(),
                };
                let text = if matches!(v, liftplan_charts::sheet::Val::Num(_)) {
                    text.replace('.', &mark.to_string())
                } else {
                    text
                };
                let on_axis = (r == 5 && c > 0) || (r > 5 && c == 0);
                let text = match unit_in_axis && on_axis && matches!(v, liftplan_charts::sheet::Val::Num(_)) {
                    true => format!("{text} m"),
                    false => text,
                };
                ws.write_string(r, c as u16, &text).unwrap();
            }
        }
        let q = d.path().join("as-text.xlsx");
        wb.save(&q).unwrap();
        let (configs, reports) = read_chart(&q, &Settings::default()).unwrap();
        for (a, b) in configs.iter().zip(&numbers) {
            assert_eq!((&a.boom_lengths_m, &a.radii_m), (&b.boom_lengths_m, &b.radii_m), "{mark} {capacities}");
            let capacities_kg = |c: &liftplan_core::capacity::ChartConfig| {
                c.cells.iter().map(|x| x.as_ref().map(|x| x.capacity_kg)).collect::<Vec<_>>()
            };
            assert_eq!(capacities_kg(a), capacities_kg(b), "{mark} {capacities}");
        }
        assert_eq!(configs.len(), numbers.len());
        for r in &reports {
            if mark == ',' {
                assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
                assert!(
                    r.warnings[0].starts_with(&format!("{}!A6:M44: ", r.sheet))
                        && r.warnings[0].contains("numbers written as text with decimal commas, read as decimals"),
                    "{:?}",
                    r.warnings
                );
            } else {
                assert!(r.warnings.is_empty(), "{:?}", r.warnings);
            }
        }
    }
}

/// Numbers written as text that show no decimal mark of their own
/// ("12,500") are read with their grid's: read the common way and said,
/// cell by cell, where the grid shows none; refused where it shows both.
#[test]
fn a_number_that_reads_two_ways_is_said_or_refused() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("lb.xlsx");
    let lb = |r: f64, b: f64| cap_t(r, b).map(|t| ((t * 1000.0 / KG_PER_LB / 100.0).round() * 100.0).max(1000.0));
    let thousands = |v: f64| {
        let v = v as u64;
        if v >= 1000 { format!("{},{:03}", v / 1000, v % 1000) } else { v.to_string() }
    };
    // In pounds (or kilograms) no chart gives three decimal places: read
    // as thousands without a word. The same numbers in tonnes: read the
    // common way, and said.
    for (unit, kg_per_unit) in [("lb", KG_PER_LB), ("t", 1000.0)] {
        write_grid(
            &p,
            &format!("Capacities in {unit}"),
            "Radius (ft)",
            &[60.0, 90.0],
            &[10.0, 20.0, 30.0],
            |r, b| Some(thousands(lb(r * M_PER_FT, b * M_PER_FT)?)),
            false,
        );
        let (c, rep) = read_chart(&p, &Settings::default()).unwrap();
        let cell = c[0].lookup(60.0 * M_PER_FT, 10.0 * M_PER_FT).unwrap();
        let written = lb(10.0 * M_PER_FT, 60.0 * M_PER_FT).unwrap();
        assert!((cell.capacity_kg - written * kg_per_unit).abs() < 1e-6, "{unit}: {cell:?}");
        if unit == "lb" {
            assert!(rep[0].warnings.is_empty(), "{:?}", rep[0].warnings);
            continue;
        }
        assert_eq!(rep[0].warnings.len(), 1, "{:?}", rep[0].warnings);
        assert!(
            rep[0].warnings[0].starts_with("Chart!B5:C7: 6 numbers written as text read the common way, as no number written as text in the grid Chart!A4:C7 shows whether it writes decimals with a point or a comma (Chart!B5 '")
                && rep[0].warnings[0].ends_with(", the comma separating thousands): CHECK them against the chart"),
            "{:?}",
            rep[0].warnings
        );
    }

    let p = d.path().join("both.xlsx");
    write_metric_grid(&p, |r, b| {
        Some(match (r, b) {
            (4.0, 20.0) => "66,7".to_string(),
            (4.0, 30.0) => "44.4".to_string(),
            (6.0, 20.0) => "50,000".to_string(),
            _ => format!("{:.1}", cap_t(r, b)?),
        })
    });
    let e = read_chart(&p, &Settings::default()).unwrap_err().to_string();
    assert!(
        e.contains("[Chart!B6]") && e.contains("'50,000' may be 50 or 50000, and the grid writes decimals with a comma (Chart!B5 '66,7') and with a point (Chart!C5 '44.4')"),
        "{e}"
    );
}

#[test]
fn bad_cells_are_refused_with_sheet_and_cell() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("bad.xlsx");
    write_metric_grid(&p, |r, b| {
        Some(if (r, b) == (6.0, 30.0) { "heavy".into() } else { format!("{}", cap_t(r, b)?) })
    });
    let e = read_chart(&p, &Settings::default()).unwrap_err().to_string();
    assert!(e.contains("bad.xlsx [Chart!C6]") && e.contains("heavy"), "{e}");

    let p = d.path().join("rise.xlsx");
    write_metric_grid(&p, |r, b| Some(if (r, b) == (10.0, 20.0) { "99".into() } else { format!("{}", cap_t(r, b)?) }));
    let e = read_chart(&p, &Settings::default()).unwrap_err().to_string();
    assert!(e.contains("[Chart!B7]") && e.contains("rises with radius"), "{e}");

    let p = d.path().join("typo.xlsx");
    write_metric_grid(&p, |r, b| {
        let c = cap_t(r, b)?;
        Some(if (r, b) == (6.0, 20.0) {
            format!("{c:.1}").replace('.', ",")
        } else if (r, b) == (4.0, 30.0) {
            format!("{c:.1}t")
        } else {
            format!("{c:.1}")
        })
    });
    let (c, rep) = read_chart(&p, &Settings::default()).unwrap();
    assert!(rep[0].warnings.iter().any(|w| w.contains("Chart!B6")), "{:?}", rep[0].warnings);
    assert!(
        (c[0].lookup(20.0, 6.0).unwrap().capacity_kg - (cap_t(6.0, 20.0).unwrap() * 10.0).round() * 100.0).abs() < 1e-6
    );

    let p = d.path().join("kg.xlsx");
    write_metric_grid(&p, |r, b| {
        let c = cap_t(r, b)?;
        Some(if (r, b) == (6.0, 30.0) { format!("{} kg", c * 1000.0) } else { format!("{c}") })
    });
    let e = read_chart(&p, &Settings::default()).unwrap_err().to_string();
    assert!(e.contains("[Chart!C6]") && e.contains("kg"), "{e}");
}

/// Booms 50 and 80 across row 2 (D2:E2), radii 10, 20, 30 down column C,
/// capacities falling with both, and no label or unit anywhere.
fn small_grid(ws: &mut rust_xlsxwriter::Worksheet) {
    small_grid_at(ws, 1);
}

/// [`small_grid`] under labels naming its units: "Radius m" (A1) and
/// "Boom m / capacity t" (B1).
fn labelled_small_grid(ws: &mut rust_xlsxwriter::Worksheet) {
    ws.write_string(0, 0, "Radius m").unwrap();
    ws.write_string(0, 1, "Boom m / capacity t").unwrap();
    small_grid(ws);
}

/// [`small_grid`] with its boom lengths on row `booms_row` (0-based).
fn small_grid_at(ws: &mut rust_xlsxwriter::Worksheet, booms_row: u32) {
    small_grid_at_col(ws, booms_row, 0);
}

/// [`small_grid_at`] moved `col0` columns right.
fn small_grid_at_col(ws: &mut rust_xlsxwriter::Worksheet, booms_row: u32, col0: u16) {
    for (j, b) in [50.0, 80.0].iter().enumerate() {
        ws.write_number(booms_row, col0 + 3 + j as u16, *b).unwrap();
    }
    for (i, r) in [10.0, 20.0, 30.0].iter().enumerate() {
        ws.write_number(booms_row + 1 + i as u32, col0 + 2, *r).unwrap();
        for j in 0..2 {
            ws.write_number(booms_row + 1 + i as u32, col0 + 3 + j, 100.0 - 20.0 * i as f64 - 10.0 * j as f64).unwrap();
        }
    }
}

#[test]
fn explicit_mapping_wins() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("odd.xlsx");
    // No labels or units at all: detection would assume; the mapping says ft/kips.
    let mut wb = Workbook::new();
    let ws = wb.add_worksheet().set_name("S").unwrap();
    small_grid(ws);
    wb.save(&p).unwrap();
    let s = Settings {
        table: vec![TableMapping {
            file: "odd.xlsx".into(),
            sheet: "S".into(),
            config: "mapped".into(),
            across: "D2:E2".into(),
            down: "C3:C5".into(),
            transposed: false,
            length_unit: Some(liftplan_core::units::LengthUnit::Ft),
            capacity_unit: Some(liftplan_core::units::MassUnit::Kips),
        }],
        ..Default::default()
    };
    let (c, _) = read_chart(&p, &s).unwrap();
    assert_eq!(c[0].name, "mapped");
    // A table naming a sheet the workbook does not have is refused, not
    // passed by while the sheet is searched without it.
    let mut typo = s.clone();
    typo.table[0].sheet = "s".into();
    let e = read_chart(&p, &typo).unwrap_err().to_string();
    assert!(
        e.ends_with(
            "odd.xlsx: [[charts.table]] 'mapped' names sheet 's', which this workbook does not have (its sheets: 'S')"
        ),
        "{e}"
    );
    assert!((c[0].radii_m[0] - 10.0 * M_PER_FT).abs() < 1e-12);
    assert!(
        (c[0].lookup(50.0 * M_PER_FT, 10.0 * M_PER_FT).unwrap().capacity_kg - 100.0 * 1000.0 * KG_PER_LB).abs() < 1e-6
    );
    // Detection finds the grid but no unit: refused, naming the grid, not
    // read as metres and tonnes (kips as tonnes would be 2.2 times too strong,
    // pounds 2205 times).
    let e = read_chart(&p, &Settings::default()).unwrap_err().to_string();
    assert!(e.contains("[S!C2]") && e.contains("no length unit found") && e.contains("length_unit"), "{e}");
    let length_only = Settings { length_unit: Some(liftplan_core::units::LengthUnit::Ft), ..Default::default() };
    let e = read_chart(&p, &length_only).unwrap_err().to_string();
    assert!(e.contains("no capacity unit found") && e.contains("capacity_unit"), "{e}");
    // The project says the units of grids whose labels name none.
    let both = Settings { capacity_unit: Some(liftplan_core::units::MassUnit::Kips), ..length_only };
    let (c, reports) = read_chart(&p, &both).unwrap();
    assert!(
        (c[0].lookup(50.0 * M_PER_FT, 10.0 * M_PER_FT).unwrap().capacity_kg - 100.0 * 1000.0 * KG_PER_LB).abs() < 1e-6
    );
    assert!(reports[0].units.found.iter().any(|f| f.contains("as [charts] capacity_unit says")), "{reports:?}");
    // `inspect` shows what the file holds, saying that it names no unit.
    let shown = liftplan_charts::inspect(&p).unwrap().to_string();
    assert!(shown.contains("NO LENGTH OR CAPACITY UNIT NAMED") && shown.contains("\"length_named\":false"), "{shown}");
}

/// Units the labels name are the chart's, whatever `[charts]` says for
/// grids whose labels name none.
#[test]
fn units_the_labels_name_win_over_the_project_default() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("named.xlsx");
    let mut wb = Workbook::new();
    let ws = wb.add_worksheet().set_name("S").unwrap();
    ws.write_string(0, 3, "Capacities in t, lengths in m").unwrap();
    small_grid(ws);
    wb.save(&p).unwrap();
    let s = Settings {
        length_unit: Some(liftplan_core::units::LengthUnit::Ft),
        capacity_unit: Some(liftplan_core::units::MassUnit::Lb),
        ..Default::default()
    };
    let (c, reports) = read_chart(&p, &s).unwrap();
    assert_eq!(c[0].radii_m, vec![10.0, 20.0, 30.0]);
    assert!((c[0].lookup(50.0, 10.0).unwrap().capacity_kg - 100_000.0).abs() < 1e-6);
    assert_eq!(reports[0].units.found, vec!["capacity in t", "radius in m"], "{reports:?}");
}

/// The same chart in Excel's binary workbook format (xlsb) and the legacy
/// one (xls), both fixtures written by scripts beside them: the same
/// configuration, booms, radii and capacities, each capacity from the same
/// cell.
#[test]
fn an_xlsb_chart_reads_as_its_xls_twin() {
    let fixture = |name: &str| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/charts").join(name);
    let (xlsb, _) = read_chart(&fixture("chart.xlsb"), &Settings::default()).unwrap();
    let (xls, _) = read_chart(&fixture("chart.xls"), &Settings::default()).unwrap();
    assert_eq!(xlsb.len(), 1);
    assert_eq!(xlsb[0].name, "Main boom");
    assert_eq!(xlsb[0].boom_lengths_m, vec![20.0, 30.0, 40.0]);
    assert_eq!(xlsb[0].radii_m, vec![3.0, 5.0, 8.0, 12.0]);
    assert_eq!(xlsb[0].cells.len(), 12);
    for (b, s) in xlsb[0].cells.iter().zip(&xls[0].cells) {
        let (b, s) = (b.as_ref().unwrap(), s.as_ref().unwrap());
        assert_eq!(b.capacity_kg, s.capacity_kg);
        assert_eq!(b.cell.replace("chart.xlsb", "chart.xls"), s.cell);
    }
}

/// A lift of a 4 x 2 x 2 m load of `mass_t` on the built-in `crane` (its
/// 40 m boom where it luffs) at the origin, with chart configuration
/// `config`, picked at x `pick_x_m` and set 25 m north of the crane.
fn lift_on(crane: &str, config: &str, mass_t: f64, pick_x_m: f64) -> liftplan_core::lift::LiftTask {
    let boom = if crane == "ac-700" { ", \"boom_m\": 40.0" } else { "" };
    let spec: liftplan_core::lift::LiftSpec = serde_json::from_str(&format!(
        r#"{{ "id": "L", "load": {{ "mass_t": {mass_t}, "size_m": [4.0, 2.0, 2.0] }},
            "crane": {{ "model": "{crane}", "position_m": [0.0, 0.0], "heading_deg": 0.0, "chart_config": "{config}"{boom} }},
            "pick": {{ "x_m": {pick_x_m}, "y_m": 0.0, "z_m": 0.0 }}, "set": {{ "x_m": 0.0, "y_m": 25.0, "z_m": 0.0 }} }}"#
    ))
    .unwrap();
    spec.resolve(liftplan_core::crane::builtin(crane).unwrap()).unwrap()
}

/// A chart of one capacity column: for a tower crane it is its jib's; for a
/// luffing crane it may be one boom length's sheet, which the lift's boom
/// must be (said, since the chart does not say it); and a chart by boom
/// length is refused for a tower crane, saying why (it read "boom length
/// 0.00 m is shorter than the chart's shortest boom").
#[test]
fn a_chart_of_one_column_and_a_chart_by_boom_length_meet_the_right_crane() {
    let d = tempfile::tempdir().unwrap();
    let (one, by_boom) = (d.path().join("tower.xlsx"), d.path().join("ac700.xlsx"));
    liftplan_fixtures::chart::write_demo_tower_chart(&one).unwrap();
    liftplan_fixtures::chart::write_demo_chart(&by_boom).unwrap();
    let table =
        |p: &Path| liftplan_core::capacity::CapacityTable { configs: read_chart(p, &Settings::default()).unwrap().0 };
    let lift = |crane: &str, config: &str| lift_on(crane, config, 5.0, 20.0);
    let tower_on_jib = liftplan_charts::lift_report(&lift("tower-hh-60", "Jib 60 m"), &table(&one)).unwrap();
    assert!(tower_on_jib.pick.is_some() && tower_on_jib.one_column_for_boom_m.is_none(), "{tower_on_jib:?}");
    let luffing_on_one = liftplan_charts::lift_report(&lift("ac-700", "Jib 60 m"), &table(&one)).unwrap();
    assert_eq!(luffing_on_one.one_column_for_boom_m, Some(40.0));
    // What the docs stage reads back of lifts.json says the lift's boom.
    let written = liftplan_charts::lifts_json(std::slice::from_ref(&luffing_on_one)).to_string();
    let read = liftplan_charts::recorded::LiftsCharted::from_json(written.as_bytes()).unwrap();
    assert_eq!(read.one_column_booms(&[lift("ac-700", "Jib 60 m")]).unwrap(), [("L".to_string(), 40.0)]);
    let s = liftplan_charts::Summary { files: vec![], configs: vec![], rows: 0, lifts: vec![luffing_on_one] };
    assert!(s.lines().iter().any(|l| l.contains("CHECK THAT IT IS THE CHART FOR THE 40.0 m BOOM")), "{:?}", s.lines());
    let tower_by_boom = liftplan_charts::lift_report(&lift("tower-hh-60", "Main boom 360"), &table(&by_boom)).unwrap();
    let e = tower_by_boom.pick_error.unwrap();
    assert!(e.contains("lists capacities by boom length (16.00 to 62.40 m), which a tower crane does not have"), "{e}");
}

/// The charts stage's line for a lift flags a load over the chart's
/// capacity as over capacity, naming where, not as a critical lift (a lift
/// at 204 % read "CRITICAL LIFT", as one at 80 % does).
#[test]
fn a_lift_over_capacity_is_said_so_not_called_critical() {
    let d = tempfile::tempdir().unwrap();
    let path = d.path().join("ac700.xlsx");
    liftplan_fixtures::chart::write_demo_chart(&path).unwrap();
    let table = liftplan_core::capacity::CapacityTable { configs: read_chart(&path, &Settings::default()).unwrap().0 };
    let report =
        |mass_t: f64| liftplan_charts::lift_report(&lift_on("ac-700", "Main boom 360", mass_t, 15.0), &table).unwrap();
    let line = |mass_t: f64| {
        let s = liftplan_charts::Summary { files: vec![], configs: vec![], rows: 0, lifts: vec![report(mass_t)] };
        s.lines().pop().unwrap()
    };
    // Utilisation grows with the load's mass: find the masses that load the
    // set position (the farther) to 90 % and 120 %, the pick staying under.
    let (u1, u2) = (report(1.0).set.unwrap().utilisation_pct, report(2.0).set.unwrap().utilisation_pct);
    let mass_for = |pct: f64| 1.0 + (pct - u1) / (u2 - u1);
    let critical = line(mass_for(90.0));
    assert!(critical.ends_with(" - CRITICAL LIFT"), "{critical}");
    let over = line(mass_for(120.0));
    assert!(report(mass_for(120.0)).pick.unwrap().utilisation_pct < 100.0, "{over}");
    assert!(over.ends_with(" - OVER CAPACITY AT SET"), "{over}");
    assert!(!over.contains("CRITICAL"), "{over}");
    let both = line(mass_for(400.0));
    assert!(both.ends_with(" - OVER CAPACITY AT PICK AND SET"), "{both}");
}

/// A workbook that keeps its chart's notes on a sheet of their own: a
/// footnote mark is looked up there when the chart's sheet has no note of
/// that mark, never on another chart's sheet (whose notes are its own), and
/// a second sheet of notes with the same mark is named, not chosen between.
#[test]
fn a_footnote_on_a_sheet_of_notes_is_quoted() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("notes.xlsx");
    let grid = |ws: &mut rust_xlsxwriter::Worksheet, marked: &str| {
        labelled_small_grid(ws);
        ws.write_string(3, 3, marked).unwrap();
    };
    let mut wb = Workbook::new();
    wb.add_worksheet().set_name("Cover").unwrap().write_string(0, 0, "AC 700 load charts, issue 4").unwrap();
    grid(wb.add_worksheet().set_name("Chart 1").unwrap(), "80*");
    let ws = wb.add_worksheet().set_name("Chart 2").unwrap();
    grid(ws, "80*");
    ws.write_string(7, 0, "* Over the front only").unwrap();
    let ws = wb.add_worksheet().set_name("Chart 3").unwrap();
    grid(ws, "80 (3)");
    let ws = wb.add_worksheet().set_name("Notes").unwrap();
    ws.write_string(0, 0, "Notes").unwrap();
    ws.write_string(1, 0, "*").unwrap();
    ws.write_string(1, 1, "Over the rear only, 140 t counterweight").unwrap();
    ws.write_string(2, 0, "(2) With the jib stowed").unwrap();
    wb.save(&p).unwrap();
    let warning_of = |p: &Path, sheet: &str| {
        let (_, reports) = read_chart(p, &Settings::default()).unwrap();
        let r = reports.iter().find(|r| r.sheet == sheet).unwrap();
        assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
        r.warnings[0].clone()
    };
    assert_eq!(
        warning_of(&p, "Chart 1"),
        "Chart 1!D4: footnote mark dropped from '80*'; none is marked '*' on sheet Chart 1, and the footnote so \
         marked on a sheet of notes, Notes!A2, reads: \"Over the rear only, 140 t counterweight\""
    );
    // A chart's own note first.
    assert!(warning_of(&p, "Chart 2").ends_with("its footnote, Chart 2!A8, reads: \"Over the front only\""));
    assert_eq!(
        warning_of(&p, "Chart 3"),
        "Chart 3!D4: footnote mark dropped from '80 (3)'; no footnote marked '(3)' was found on sheet Chart 3 nor \
         on the workbook's sheets without a chart (Cover, Notes): read the chart's notes for it"
    );
    // Two sheets of notes with a note marked '*': the first is quoted, the
    // other named.
    let ws = wb.add_worksheet().set_name("Remarks").unwrap();
    ws.write_string(4, 1, "* Tyres, not outriggers").unwrap();
    wb.save(&p).unwrap();
    assert!(
        warning_of(&p, "Chart 1").ends_with(
            "Notes!A2, reads: \"Over the rear only, 140 t counterweight\"; Remarks!B5 also open with '*': check which \
             note applies"
        ),
        "{}",
        warning_of(&p, "Chart 1")
    );
}

/// A workbook whose wind speed is stated on a sheet of notes (a sheet with
/// no grid): the grids whose own region states none take it, with its
/// sheet named; a grid that states its own keeps its own.
#[test]
fn a_sheet_of_notes_states_the_wind_speed_for_grids_that_state_none() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("notes.xlsx");
    let mut wb = Workbook::new();
    labelled_small_grid(wb.add_worksheet().set_name("Main").unwrap());
    let ws = wb.add_worksheet().set_name("Jib").unwrap();
    labelled_small_grid(ws);
    ws.write_string(6, 0, "Permissible wind speed 7.0 m/s").unwrap();
    let ws = wb.add_worksheet().set_name("Notes").unwrap();
    ws.write_string(0, 0, "General notes").unwrap();
    ws.write_string(3, 0, "Permissible wind speed 9.0 m/s (3 s gust)").unwrap();
    wb.save(&p).unwrap();
    let (_, reports) = read_chart(&p, &Settings::default()).unwrap();
    let main = reports.iter().find(|r| r.sheet == "Main").unwrap();
    let jib = reports.iter().find(|r| r.sheet == "Jib").unwrap();
    assert_eq!(main.wind_ms.iter().map(|w| (w.value, w.cell.as_str())).collect::<Vec<_>>(), [(9.0, "Notes!A4")]);
    assert_eq!(jib.wind_ms.iter().map(|w| (w.value, w.cell.as_str())).collect::<Vec<_>>(), [(7.0, "Jib!A7")]);
    assert_eq!(main.stated_said(), "; states wind 9.0 m/s (Notes!A4)");
    assert_eq!(jib.stated_said(), "; states wind 7.0 m/s (A7)");
}

/// What a sheet states in words beside its grids: each grid's title just
/// above it and its notes under it, down to the next grid's title, are its
/// own. `inspect` shows them.
#[test]
fn the_wind_speed_and_counterweight_a_sheet_states_are_read_per_grid() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("stated.xlsx");
    let mut wb = Workbook::new();
    let ws = wb.add_worksheet().set_name("S").unwrap();
    let grid = |ws: &mut rust_xlsxwriter::Worksheet, row0: u32, title: &str| {
        ws.write_string(row0, 0, title).unwrap();
        ws.write_string(row0 + 1, 0, "Radius m").unwrap();
        ws.write_string(row0 + 1, 1, "Boom m / capacity t").unwrap();
        small_grid_at(ws, row0 + 2);
    };
    grid(ws, 0, "Main boom, counterweight 70 t");
    ws.write_string(7, 0, "Permissible wind speed 9.8 m/s").unwrap();
    grid(ws, 10, "Main boom, counterweight 140 t");
    ws.write_string(17, 0, "Max. wind speed 25.2 km/h with the jib").unwrap();
    wb.save(&p).unwrap();
    let (_, reports) = read_chart(&p, &Settings::default()).unwrap();
    assert_eq!(reports.len(), 2, "{reports:?}");
    let values = |v: &[liftplan_core::capacity::StatedOnChart]| -> Vec<(f64, String)> {
        v.iter().map(|s| ((s.value * 1000.0).round() / 1000.0, s.cell.clone())).collect()
    };
    assert_eq!(values(&reports[0].wind_ms), [(9.8, "S!A8".to_string())]);
    assert_eq!(values(&reports[0].counterweight_kg), [(70_000.0, "S!A1".to_string())]);
    assert_eq!(values(&reports[1].wind_ms), [(7.0, "S!A18".to_string())]);
    assert_eq!(values(&reports[1].counterweight_kg), [(140_000.0, "S!A11".to_string())]);
    assert!(
        reports[0].stated_said().starts_with("; states wind 9.8 m/s (A8), counterweight 70 t (A1)"),
        "{}",
        reports[0].stated_said()
    );
    let shown = liftplan_charts::inspect(&p).unwrap().to_string();
    assert!(shown.contains("\"wind_ms\":[{\"cell\":\"S!A8\""), "{shown}");
    // Side by side, over two rows (a grid of grids): each one's title and
    // the notes under it are its own, not its neighbour's.
    let p = d.path().join("beside.xlsx");
    let mut wb = Workbook::new();
    let ws = wb.add_worksheet().set_name("S").unwrap();
    let grid = |ws: &mut rust_xlsxwriter::Worksheet, row0: u32, col0: u16, title: &str, note: &str| {
        ws.write_string(row0, col0, title).unwrap();
        ws.write_string(row0 + 1, col0, "Radius m").unwrap();
        ws.write_string(row0 + 1, col0 + 1, "Boom m / capacity t").unwrap();
        small_grid_at_col(ws, row0 + 2, col0);
        ws.write_string(row0 + 7, col0, note).unwrap();
    };
    grid(ws, 0, 0, "Main boom, counterweight 70 t", "Permissible wind speed 9.8 m/s");
    grid(ws, 0, 6, "Main boom, counterweight 140 t", "Permissible wind speed 11.1 m/s");
    grid(ws, 10, 0, "Main boom, counterweight 100 t", "Max. wind speed 25.2 km/h");
    grid(ws, 10, 6, "Main boom, counterweight 40 t", "Max. wind speed 36 km/h");
    wb.save(&p).unwrap();
    let (_, reports) = read_chart(&p, &Settings::default()).unwrap();
    let facts: Vec<(Vec<(f64, String)>, Vec<(f64, String)>)> =
        reports.iter().map(|r| (values(&r.wind_ms), values(&r.counterweight_kg))).collect();
    let at = |ms: f64, wind: &str, kg: f64, cw: &str| (vec![(ms, format!("S!{wind}"))], vec![(kg, format!("S!{cw}"))]);
    assert_eq!(
        facts,
        [
            at(9.8, "A8", 70_000.0, "A1"),
            at(11.1, "G8", 140_000.0, "G1"),
            at(7.0, "A18", 100_000.0, "A11"),
            at(10.0, "G18", 40_000.0, "G11")
        ],
        "{reports:?}"
    );
}
