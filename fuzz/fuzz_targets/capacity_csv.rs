//! `capacity.csv`, the charts stage's table that the plan and docs stages
//! read back: damaged or hostile bytes give an error naming the file, never
//! a panic or grids of rows² cells, and a table read answers lookups at and
//! between its listed booms and radii, and outside them.
#![no_main]
use libfuzzer_sys::fuzz_target;
use liftplan_core::capacity::CapacityTable;

fuzz_target!(|data: &[u8]| {
    let Ok(table) = CapacityTable::from_csv_bytes(std::path::Path::new("capacity.csv"), data) else { return };
    for c in &table.configs {
        let between = |v: &[f64]| -> Vec<f64> {
            let mut out: Vec<f64> = v.iter().take(8).copied().collect();
            out.extend(v.windows(2).take(8).map(|w| 0.5 * (w[0] + w[1])));
            out.extend([-1.0, 0.0, 1e300, f64::NAN]);
            out
        };
        for boom in between(&c.boom_lengths_m) {
            for radius in between(&c.radii_m) {
                let _ = c.lookup(boom, radius).map(|k| (k.capacity_kg, k.cell)).map_err(|e| e.to_string());
            }
        }
        let _ = table.config(&c.name);
    }
    let _ = table.rows();
});
