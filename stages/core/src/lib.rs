//! # liftplan-core
//!
//! The shared vocabulary of liftplan. Every stage crate depends on this one and on
//! nothing else of ours; stages exchange data only through the artifact files and
//! types defined here.
//!
//! | module | what it holds |
//! |---|---|
//! | [`location`] | file + byte / line / `sheet!cell` places for error messages |
//! | [`units`] | the SI-inside, units-at-the-edges conversions |
//! | [`frame`] | site frame, poses, axis-aligned boxes |
//! | [`guard`] | the boundary around third-party parsers that panic on damaged input |
//! | [`obb`] | oriented boxes: crane parts and their exact footprint/height facts |
//! | [`cloud`] | point clouds (columns) |
//! | [`mesh`] | triangle meshes with part/group provenance |
//! | [`names`] | names from others' files as liftplan keeps them: bounded, no control characters |
//! | [`crane`] | crane model files, placement, forward and inverse kinematics |
//! | [`outriggers`] | a mobile crane's pad loads and the pressure under its mats |
//! | [`capacity`] | load-chart grids and the never-interpolate-upwards rule |
//! | [`chart_json`] | what each chart configuration's sheet states, read back from the charts stage's `chart.json` |
//! | [`las_file`] | LAS/LAZ files' structure checked before the `las` and `laz` crates trust it |
//! | [`lift`] | the lift request and its validated form |
//! | [`obstacle`] | boxes placed by hand: what is on site that the scans and model do not hold |
//! | [`wind`] | the wind speed up to which a mobile crane may lift a load |
//! | [`artifact`] | checked binary artifact files and atomic writes |
//! | [`image`] | RGB rasters, PNG output, labels and colour ramps |
//! | [`rng`] | the seeded random streams |
//! | [`testing`] | what the property tests share (their case count) |
//!
//! ```
//! use liftplan_core::crane::{builtin, CraneSetup, Placement, LoadShape, LoadPose};
//! let model = builtin("ltm-1100").unwrap();
//! let crane = CraneSetup::new(model, Placement { x_m: 0.0, y_m: 0.0, z_m: 0.0, heading_rad: 0.0, boom_length_m: 40.0 }).unwrap();
//! let load = LoadShape { size_m: [4.0, 2.0, 2.0], cog_m: [0.0; 3], rigging_height_m: 3.0 };
//! let q = crane.inverse(&LoadPose { x_m: 25.0, y_m: 5.0, z_m: 0.0, yaw_rad: 0.0 }, &load).unwrap();
//! assert!((crane.load_pose(&q, &load).x_m - 25.0).abs() < 1e-9);
//! ```

pub mod artifact;
pub mod byte_order_mark;
pub mod capacity;
pub mod chart_json;
pub mod cloud;
pub mod crane;
pub mod frame;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod guard;
pub mod image;
pub mod las_file;
pub mod lift;
pub mod location;
pub mod mesh;
pub mod names;
pub mod obb;
pub mod obstacle;
pub mod outriggers;
pub mod power_line;
pub mod reeving;
pub mod rng;
pub mod slings;
pub mod testing;
pub mod units;
pub mod wind;

pub use location::{Location, Place};

/// For serde's `skip_serializing_if`: a quantity left out of the JSON where
/// it is zero, as a key a file does not give is (a plan's revision hashes
/// that JSON, so a key a later version learns to read leaves it as it was).
pub fn is_zero(v: &f64) -> bool {
    *v == 0.0
}
