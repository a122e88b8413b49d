//! # liftplan-plant: stage 2, plant models to one triangle mesh
//!
//! Reads PDMS/E3D binary RVM exports ([`rvm`], with their `.att` attribute files,
//! [`att`]) and BIM meshes (OBJ, PLY, STL, glTF/GLB; [`mesh_io`]), tessellates
//! RVM primitives into meshes that enclose them, at most a chord tolerance
//! outside their surfaces, never inside ([`tess`]), leaves out what the
//! selection excludes (the item being lifted, insulation, temporary works),
//! places the result in the site frame and writes:
//!
//! | file | what |
//! |---|---|
//! | `plant.mesh` | the merged mesh for later stages (a checked liftplan artifact) |
//! | `plant.ply` | the same mesh as binary PLY, with part and group per face |
//! | `plant.json` | counts per primitive kind, triangles, vertices, bbox, tolerance, excluded groups |
//!
//! Each RVM group becomes a mesh group named like the group; a collision is later
//! reported against that name. The stage never sees the cache or the CLI.
//!
//! IFC is not read: export the model from the BIM tool as glTF or OBJ.

pub mod att;
pub mod error;
pub mod mesh_io;
pub mod rvm;
pub mod tess;

use error::{PlantError, Result};
use liftplan_core::Location;
use liftplan_core::frame::Aabb;
use liftplan_core::mesh::{GroupIndex, TriMesh};
use liftplan_core::units::LengthUnit;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

pub const NAME: &str = "plant";
pub const VERSION: u32 = 2;

/// File extensions the stage reads.
pub const EXTS: &[&str] = &["rvm", "obj", "ply", "stl", "gltf", "glb", "ifc"];

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum UpAxis {
    Z,
    Y,
}

/// `[plant]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// Chord tolerance of the tessellation (m).
    pub tolerance: f64,
    /// Leave out end caps that a connected primitive covers.
    pub cull_caps: bool,
    /// Unit of OBJ/PLY/STL files (glTF is always metres, RVM millimetres).
    /// Those files state none, and their exporters differ (millimetres,
    /// metres, Revit's feet), so a project with such files must say it.
    pub unit: Option<LengthUnit>,
    /// Up axis of OBJ/PLY/STL files (glTF is always Y-up), which they do
    /// not state either: a Y-up model read as Z-up lies on its side.
    pub up_axis: Option<UpAxis>,
    /// Keep only groups whose name (or an ancestor's) matches one of these
    /// patterns (`*` and `?` wildcards); empty keeps everything.
    pub include: Vec<String>,
    /// Leave out groups whose name (or an ancestor's) matches.
    pub exclude: Vec<String>,
    /// Leave out groups whose attribute matches, e.g. `"Type=INSU"`, `"Purpose=TEMP*"`.
    pub exclude_where: Vec<String>,
    /// Keep insulation volumes (RVM INSU chunks).
    pub insulation: bool,
    /// Keep obstruction volumes (RVM OBST chunks).
    pub obstructions: bool,
    /// Placement of the model in the site frame: rotation about Z, then this
    /// translation (m).
    pub translate_m: [f64; 3],
    pub rotate_z_deg: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tolerance: 0.01,
            cull_caps: true,
            unit: None,
            up_axis: None,
            include: vec![],
            exclude: vec![],
            exclude_where: vec![],
            insulation: true,
            obstructions: true,
            translate_m: [0.0; 3],
            rotate_z_deg: 0.0,
        }
    }
}

impl Settings {
    pub fn check(&self) -> std::result::Result<(), String> {
        if !(self.tolerance.is_finite() && self.tolerance >= 1e-5) {
            return Err(format!("tolerance must be at least 0.00001 m, found {}", self.tolerance));
        }
        if !self.translate_m.iter().all(|v| v.is_finite()) || !self.rotate_z_deg.is_finite() {
            return Err("translate_m and rotate_z_deg must be finite".into());
        }
        for w in &self.exclude_where {
            if !w.contains('=') {
                return Err(format!("exclude_where entry '{w}' must look like 'Attribute=value'"));
            }
        }
        Ok(())
    }
}

/// Case-insensitive glob with `*` and `?`.
pub fn glob(pattern: &str, text: &str) -> bool {
    let p: Vec<char> = pattern.to_lowercase().chars().collect();
    let t: Vec<char> = text.to_lowercase().chars().collect();
    let (mut i, mut j, mut star, mut mark) = (0usize, 0usize, None::<usize>, 0usize);
    while j < t.len() {
        if i < p.len() && (p[i] == '?' || p[i] == t[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some(i);
            mark = j;
            i += 1;
        } else if let Some(s) = star {
            i = s + 1;
            mark += 1;
            j = mark;
        } else {
            return false;
        }
    }
    while i < p.len() && p[i] == '*' {
        i += 1;
    }
    i == p.len()
}

/// What the stage did, for `plant.json` and the run output.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Summary {
    pub files: Vec<String>,
    pub groups: usize,
    pub primitives: BTreeMap<String, usize>,
    pub triangles: usize,
    pub vertices: usize,
    pub bbox: [f64; 6],
    pub tolerance_m: f64,
    /// Largest distance from any face of an RVM primitive's mesh to its
    /// analytic surface (m); the faces lie outside the surface, never inside.
    pub max_error_m: f64,
    pub caps_culled: usize,
    pub excluded_groups: Vec<String>,
    /// `[plant] exclude` patterns that matched no group (each with the
    /// nearest group name, where one is near) and `exclude_where` rules no
    /// group's attributes met, each with its key: nothing was left out for them.
    pub exclude_unmatched: Vec<String>,
    /// Where each excluded group stands, as the smallest upright box around
    /// it in the site frame (one per name).
    pub excluded_boxes: Vec<liftplan_core::mesh::ModelBox>,
    /// The excluded groups' points in model coordinates, by name, until
    /// they are placed and boxed, and where each of its parts' points end
    /// (an RVM primitive's box corners, a mesh's connected piece), which are
    /// boxed as its parts.
    #[serde(skip)]
    pub excluded_points: Vec<(String, Vec<[f64; 3]>, Vec<usize>)>,
    /// `[plant] exclude_where` rules some group's attributes met, and how
    /// many attribute files were read, for saying those that met none.
    #[serde(skip)]
    pub exclude_where_matched: std::collections::BTreeSet<String>,
    #[serde(skip)]
    pub attribute_files: usize,
    /// Every group name met, for checking the selection's patterns.
    #[serde(skip)]
    pub seen_groups: Vec<String>,
    /// RVM line primitives, which have no surface: not in the mesh.
    pub lines_skipped: usize,
    /// glTF primitives drawn as points or lines ("file: node (mode)"), OBJ
    /// line and point elements ("file: n line or point elements") and files
    /// with no faces at all, which have no surface: not in the mesh.
    pub not_surfaces: Vec<String>,
    /// How OBJ/PLY/STL files were read (`[plant] unit` and `up_axis`), and
    /// how many there were.
    pub meshes_read_as: Option<String>,
    pub unitless_mesh_files: usize,
    /// Group names longer than [`liftplan_core::mesh::MAX_GROUP_NAME_CHARS`]
    /// characters, kept as their first that many: of the mesh's groups and
    /// of those left out.
    #[serde(default)]
    pub names_shortened: usize,
}

impl Summary {
    pub fn lines(&self) -> Vec<String> {
        let prims: usize = self.primitives.values().sum();
        let mut v = vec![format!(
            "{} files, {} groups, {prims} primitives -> {} triangles (enclosing each primitive, at most {} m outside it; {} caps culled)",
            self.files.len(),
            self.groups,
            self.triangles,
            self.tolerance_m,
            self.caps_culled
        )];
        if !self.excluded_groups.is_empty() {
            v.push(format!("excluded {} groups: {}", self.excluded_groups.len(), first_five(&self.excluded_groups)));
        }
        for p in &self.exclude_unmatched {
            v.push(format!("[plant] {p} matches no group: NOTHING WAS LEFT OUT for it"));
        }
        if let Some(how) = &self.meshes_read_as {
            v.push(format!(
                "OBJ/PLY/STL coordinates {how}, as [plant] unit and up_axis say: {} file{}",
                self.unitless_mesh_files,
                if self.unitless_mesh_files == 1 { "" } else { "s" }
            ));
        }
        // Left out of the obstacles for want of a surface: said here, where
        // the plan's inputs page shows it, so that a cable drawn as a line
        // is not taken for checked.
        if self.lines_skipped > 0 {
            v.push(format!(
                "NOT AN OBSTACLE: {} RVM line primitives (no surface to keep; model such items as solids)",
                self.lines_skipped
            ));
        }
        if !self.not_surfaces.is_empty() {
            v.push(format!(
                "NOT AN OBSTACLE: {} items without a surface (points, lines; nothing to keep: model such items as solids): {}",
                self.not_surfaces.len(),
                first_five(&self.not_surfaces)
            ));
        }
        if self.names_shortened > 0 {
            v.push(format!(
                "{} group names longer than {} characters are kept as their first {}, \"... #\" and a tag of the whole name (the plan's pages name what a crane comes closest to by them)",
                self.names_shortened,
                liftplan_core::mesh::MAX_GROUP_NAME_CHARS,
                liftplan_core::mesh::MAX_GROUP_NAME_CHARS
            ));
        }
        v
    }
}

/// The name in `names` nearest `pattern` by edit distance (case ignored),
/// where it is at most a quarter of the pattern's length (and at least 2)
/// away; of equal distances the first.
fn nearest_name<'a>(pattern: &str, names: &'a [String]) -> Option<&'a str> {
    let p: Vec<char> = pattern.to_lowercase().chars().collect();
    let limit = (p.len() / 4).max(2);
    let mut best: Option<(usize, &str)> = None;
    let mut row: Vec<usize> = Vec::new();
    for name in names {
        let n: Vec<char> = name.to_lowercase().chars().collect();
        if n.len().abs_diff(p.len()) > limit {
            continue;
        }
        // Levenshtein, one row at a time.
        row.clear();
        row.extend(0..=n.len());
        for (i, pc) in p.iter().enumerate() {
            let mut diag = row[0];
            row[0] = i + 1;
            for (j, nc) in n.iter().enumerate() {
                let next = (diag + usize::from(pc != nc)).min(row[j] + 1).min(row[j + 1] + 1);
                diag = row[j + 1];
                row[j + 1] = next;
            }
        }
        let d = row[n.len()];
        if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, name));
        }
    }
    best.map(|(_, n)| n)
}

/// Each of `names` as the plant stage keeps it
/// ([`liftplan_core::mesh::group_name_kept`]); how many were shortened
/// (not counting those only whose control characters were replaced).
fn keep_group_names<'a>(names: impl IntoIterator<Item = &'a mut String>) -> usize {
    let mut shortened = 0;
    for name in names {
        if let std::borrow::Cow::Owned(kept) = liftplan_core::mesh::group_name_kept(name) {
            shortened += usize::from(name.chars().nth(liftplan_core::mesh::MAX_GROUP_NAME_CHARS).is_some());
            *name = kept;
        }
    }
    shortened
}

/// The first five of `items`, and "..." when there are more; each of a
/// model's names as the plant stage keeps it.
fn first_five(items: &[String]) -> String {
    let shown: Vec<_> = items.iter().take(5).map(|s| liftplan_core::mesh::group_name_kept(s)).collect();
    format!("{}{}", shown.join(", "), if items.len() > 5 { ", ..." } else { "" })
}

/// A circular end of a primitive in model coordinates, for cap culling.
struct End {
    prim: usize,
    which: usize,
    center: [f64; 3],
    normal: [f64; 3],
    radius: f64,
}

fn circular_ends(prims: &[(&rvm::Primitive, usize)]) -> Vec<End> {
    use rvm::Shape;
    let mut ends = Vec::new();
    for (i, (p, _)) in prims.iter().enumerate() {
        let m = &p.matrix;
        let s = tess::matrix_scale(m);
        let dir = |v: [f64; 3]| {
            let a = tess::transform(m, v);
            let o = tess::transform(m, [0.0; 3]);
            let d = [a[0] - o[0], a[1] - o[1], a[2] - o[2]];
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-30);
            [d[0] / n, d[1] / n, d[2] / n]
        };
        let mut push = |which: usize, c: [f64; 3], n: [f64; 3], r: f64| {
            ends.push(End { prim: i, which, center: tess::transform(m, c), normal: dir(n), radius: r * s })
        };
        match &p.shape {
            Shape::Cylinder { radius, height } => {
                let (r, h) = (*radius as f64, *height as f64);
                push(0, [0.0, 0.0, -h / 2.0], [0.0, 0.0, -1.0], r);
                push(1, [0.0, 0.0, h / 2.0], [0.0, 0.0, 1.0], r);
            }
            Shape::Snout { radius_b, radius_t, height, offset, bshear, tshear }
                if bshear.iter().chain(tshear).all(|a| a.abs() < 1e-6) =>
            {
                let (ox, oy, h) = (offset[0] as f64 / 2.0, offset[1] as f64 / 2.0, *height as f64);
                push(0, [-ox, -oy, -h / 2.0], [0.0, 0.0, -1.0], *radius_b as f64);
                push(1, [ox, oy, h / 2.0], [0.0, 0.0, 1.0], *radius_t as f64);
            }
            Shape::CircularTorus { offset, radius, angle } => {
                let (o, a) = (*offset as f64, *angle as f64);
                push(0, [o, 0.0, 0.0], [0.0, -1.0, 0.0], *radius as f64);
                push(1, [o * a.cos(), o * a.sin(), 0.0], [-a.sin(), a.cos(), 0.0], *radius as f64);
            }
            _ => {}
        }
    }
    ends
}

/// Ends compared with each end, at most, when looking for the one that hides
/// its cap. Real joints meet in twos or threes; a file with thousands of ends
/// on one spot would otherwise cost the square of their number. Past this the
/// cap is kept, which is always safe: culling only saves triangles.
const CAP_CANDIDATES: usize = 64;

/// Radii of two ends this close (m) are the same radius: a file's `f32`
/// values of one radius differ by far less, a ring this wide left open is far
/// inside any tolerance.
const SAME_RADIUS_M: f64 = 1e-6;

/// Caps to emit per primitive: an end is left open when another primitive's end
/// sits on it (within a millimetre), faces the other way and is at least as
/// wide ([`SAME_RADIUS_M`]), so the cap would be hidden inside the joint. The
/// wider end of a joint of two radii keeps its cap: the ring between the two
/// would otherwise be open (it was, up to 5 % of the radius, until the
/// twenty-eighth stop).
fn caps_for(prims: &[(&rvm::Primitive, usize)]) -> (Vec<tess::Caps>, usize) {
    let ends = circular_ends(prims);
    let mut caps = vec![[true, true]; prims.len()];
    let key =
        |c: &[f64; 3]| [(c[0] * 1000.0).round() as i64, (c[1] * 1000.0).round() as i64, (c[2] * 1000.0).round() as i64];
    let mut grid: std::collections::HashMap<[i64; 3], Vec<usize>> = std::collections::HashMap::new();
    for (k, e) in ends.iter().enumerate() {
        grid.entry(key(&e.center)).or_default().push(k);
    }
    let mut culled = 0;
    for (k, e) in ends.iter().enumerate() {
        let c = key(&e.center);
        let mut hidden = false;
        let mut compared = 0;
        'n: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    // Saturating: a damaged file's coordinates can round to
                    // i64::MAX millimetres.
                    let near = [c[0].saturating_add(dx), c[1].saturating_add(dy), c[2].saturating_add(dz)];
                    for &o in grid.get(&near).into_iter().flatten() {
                        let f = &ends[o];
                        if o == k || f.prim == e.prim {
                            continue;
                        }
                        compared += 1;
                        if compared > CAP_CANDIDATES {
                            break 'n;
                        }
                        let d2: f64 = (0..3).map(|i| (e.center[i] - f.center[i]).powi(2)).sum();
                        let dot: f64 = (0..3).map(|i| e.normal[i] * f.normal[i]).sum();
                        // The other end's disk must cover this one's: were
                        // this end wider, the ring between them would be
                        // left open with both caps culled.
                        if d2 < 1e-6 && dot < -0.99 && e.radius <= f.radius + SAME_RADIUS_M {
                            hidden = true;
                            break 'n;
                        }
                    }
                }
            }
        }
        if hidden {
            caps[e.prim][e.which] = false;
            culled += 1;
        }
    }
    (caps, culled)
}

/// The most triangles a plant model may have, all its files together.
///
/// A model's size is not bounded by its files' size: an RVM primitive of a
/// hundred bytes can ask the tessellation for millions of triangles (a large
/// torus at a fine tolerance, or a matrix that scales it up), and a glTF scene
/// can place one mesh many times. Each triangle costs about 40 bytes here and
/// more in the depth map and the validator, so past this the stage refuses the
/// model, naming what makes it large, before it allocates the triangles. The
/// thesis' plant has 376,008 triangles; the PDMS sample export makes 18,833
/// at the default tolerance.
pub const MAX_TRIANGLES: u64 = 100_000_000;

/// Converts an RVM file (with attributes, if any) into a mesh. `path` names
/// the file in errors; the model may add at most `room` triangles (see
/// [`MAX_TRIANGLES`]).
pub fn rvm_to_mesh(
    path: &Path,
    file: &rvm::RvmFile,
    attrs: Option<&att::Attributes>,
    s: &Settings,
    summary: &mut Summary,
    room: u64,
) -> Result<TriMesh> {
    // Decide per group whether it is kept, walking the hierarchy.
    let mut kept: Vec<(&rvm::Primitive, usize)> = Vec::new();
    let mut group_names: Vec<String> = Vec::new();
    fn matches_where(attrs: Option<&att::Attributes>, group: &str, rules: &[String]) -> bool {
        let Some(a) = attrs else { return false };
        rules.iter().any(|r| {
            let (k, v) = r.split_once('=').unwrap_or((r, "*"));
            a.get(group, k.trim()).is_some_and(|val| glob(v.trim(), val))
        })
    }
    fn go<'a>(
        g: &'a rvm::Group,
        ancestors_ok: Option<bool>,
        attrs: Option<&att::Attributes>,
        s: &Settings,
        kept: &mut Vec<(&'a rvm::Primitive, usize)>,
        names: &mut Vec<String>,
        excluded: &mut Vec<(String, Vec<[f64; 3]>)>,
        seen: &mut Vec<String>,
    ) {
        seen.push(g.name.clone());
        let role_ok = |p: &rvm::Primitive| match p.role {
            rvm::Role::Primitive => true,
            rvm::Role::Insulation => s.insulation,
            rvm::Role::Obstruction => s.obstructions,
        };
        if s.exclude.iter().any(|p| glob(p, &g.name)) || matches_where(attrs, &g.name, &s.exclude_where) {
            // Where it stands, for comparing with a lift's set position: the
            // corners of its primitives' boxes (the file's own, in each
            // primitive's frame), not tessellated, so that leaving out a
            // large part of a model costs nothing.
            fn corners(g: &rvm::Group, role_ok: &dyn Fn(&rvm::Primitive) -> bool, out: &mut Vec<[f64; 3]>) {
                for p in g.primitives.iter().filter(|p| role_ok(p)) {
                    let b = p.bbox_local.map(f64::from);
                    out.extend((0..8).map(|k| {
                        tess::transform(
                            &p.matrix,
                            [
                                b[if k & 1 == 0 { 0 } else { 3 }],
                                b[if k & 2 == 0 { 1 } else { 4 }],
                                b[if k & 4 == 0 { 2 } else { 5 }],
                            ],
                        )
                    }));
                }
                for c in &g.children {
                    corners(c, role_ok, out);
                }
            }
            let mut points = Vec::new();
            corners(g, &role_ok, &mut points);
            excluded.push((g.name.clone(), points));
            return;
        }
        // `None`: no include pattern matched yet on the way down.
        let included =
            if s.include.is_empty() || ancestors_ok == Some(true) || s.include.iter().any(|p| glob(p, &g.name)) {
                Some(true)
            } else {
                ancestors_ok
            };
        if included == Some(true) && !g.primitives.is_empty() {
            let id = names.len();
            names.push(g.name.clone());
            for p in g.primitives.iter().filter(|p| role_ok(p)) {
                kept.push((p, id));
            }
        }
        for c in &g.children {
            go(c, included, attrs, s, kept, names, excluded, seen);
        }
    }
    let mut excluded = Vec::new();
    let first_seen = summary.seen_groups.len();
    for g in &file.groups {
        go(g, None, attrs, s, &mut kept, &mut group_names, &mut excluded, &mut summary.seen_groups);
    }
    // Which exclude_where rules this file's attributes meet.
    for rule in &s.exclude_where {
        if summary.seen_groups[first_seen..].iter().any(|g| matches_where(attrs, g, std::slice::from_ref(rule))) {
            summary.exclude_where_matched.insert(rule.clone());
        }
    }
    for (name, points) in excluded {
        summary.excluded_groups.push(name.clone());
        let ends = (1..=points.len() / 8).map(|k| 8 * k).collect();
        summary.excluded_points.push((name, points, ends));
    }
    summary.groups += file.group_count();
    for (k, n) in file.primitive_counts() {
        *summary.primitives.entry(k.name().to_string()).or_insert(0) += n;
    }
    let (caps, culled) = if s.cull_caps { caps_for(&kept) } else { (vec![[true, true]; kept.len()], 0) };
    summary.caps_culled += culled;
    let tol = s.tolerance;
    let tol_local = |p: &rvm::Primitive| tol / tess::matrix_scale(&p.matrix).max(1e-12);
    let counts: Vec<u64> =
        kept.par_iter().zip(caps.par_iter()).map(|((p, _), c)| tess::triangle_count(p, tol_local(p), *c)).collect();
    let total: u64 = counts.iter().sum();
    if total > room {
        let (i, most) = counts.iter().enumerate().max_by_key(|(_, n)| **n).map_or((0, 0), |(i, n)| (i, *n));
        let (p, g) = kept[i];
        let before = if room < MAX_TRIANGLES { " with the plant files read before it" } else { "" };
        return Err(PlantError::at(
            Location::file(path),
            format!(
                "tessellated at a tolerance of {tol} m this model makes {total} triangles, more than a plant may \
                 have ({MAX_TRIANGLES}{before}); the largest primitive, a {} of group {} at byte {}, makes {most} \
                 alone. Raise [plant] tolerance, or leave groups out with [plant] exclude",
                p.shape.kind().name(),
                liftplan_core::mesh::group_name_kept(&group_names[g]),
                p.offset
            ),
        ));
    }
    let tessellated: Vec<Option<(tess::Tess, usize, [f32; 12])>> = kept
        .par_iter()
        .zip(caps.par_iter())
        .map(|((p, g), c)| tess::tessellate(p, tol_local(p), *c).map(|t| (t, *g, p.matrix)))
        .collect();
    let mut mesh = TriMesh::default();
    let mut index = GroupIndex::of(&mesh);
    let gids: Vec<u32> = group_names.iter().map(|n| index.id(&mut mesh, n)).collect();
    for item in tessellated {
        let Some((t, g, m)) = item else {
            summary.lines_skipped += 1;
            continue;
        };
        let verts: Vec<[f64; 3]> = t.vertices.iter().map(|v| tess::transform(&m, *v)).collect();
        // One mesh part per primitive part (torus segments are parts of their own).
        mesh.add_parts(gids[g], &t.convex, &verts, &t.triangles, &t.part);
    }
    Ok(mesh)
}

/// Reads one plant file into a mesh in model coordinates, adding its
/// triangles to `summary.triangles`. A file that would take the plant past
/// [`MAX_TRIANGLES`] (with the triangles already in `summary`) is refused.
pub fn read_file(path: &Path, s: &Settings, summary: &mut Summary) -> Result<TriMesh> {
    let room = MAX_TRIANGLES.saturating_sub(summary.triangles as u64);
    let m = read_model(path, s, summary, room)?;
    if m.triangle_count() as u64 > room {
        return Err(PlantError::at(
            Location::file(path),
            format!(
                "this file has {} triangles, and the plant {} before it: more than a plant may have \
                 ({MAX_TRIANGLES}); simplify the model",
                m.triangle_count(),
                summary.triangles
            ),
        ));
    }
    summary.triangles += m.triangle_count();
    Ok(m)
}

fn read_model(path: &Path, s: &Settings, summary: &mut Summary, room: u64) -> Result<TriMesh> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let file = path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    // Only the formats that state neither need the settings.
    let imp = || -> Result<mesh_io::Import> {
        match (s.unit, s.up_axis) {
            (Some(unit), Some(up)) => Ok(mesh_io::Import { scale: unit.to_m(), y_up: up == UpAxis::Y }),
            (unit, up) => {
                let missing: Vec<&str> =
                    [(unit.is_none(), "unit (m, mm, cm, ft or in)"), (up.is_none(), "up_axis (z or y)")]
                        .into_iter()
                        .filter_map(|(m, what)| m.then_some(what))
                        .collect();
                Err(PlantError::at(
                    Location::file(path),
                    format!(
                        "a .{ext} file states neither its length unit nor its up axis, and exporters differ (millimetres, metres, Revit's feet; Z or Y up): set [plant] {}",
                        missing.join(" and ")
                    ),
                ))
            }
        }
    };
    let m = match ext.as_str() {
        "rvm" => {
            let f = rvm::read(path)?;
            let attrs = match att::beside(path) {
                Some(att_path) => {
                    summary.attribute_files += 1;
                    Some(att::read(&att_path)?)
                }
                None => {
                    if !s.exclude_where.is_empty() {
                        tracing::warn!(
                            "{}: no attribute file {} beside it; exclude_where cannot apply",
                            path.display(),
                            path.with_extension("att").display()
                        );
                    }
                    None
                }
            };
            rvm_to_mesh(path, &f, attrs.as_ref(), s, summary, room)?
        }
        "obj" => {
            let (m, without) = mesh_io::read_obj(path, imp()?)?;
            if without > 0 {
                summary.not_surfaces.push(format!("{file}: {without} line or point elements"));
            }
            m
        }
        "ply" => mesh_io::read_ply(path, imp()?)?,
        "stl" => mesh_io::read_stl(path, imp()?)?,
        "gltf" | "glb" => {
            let mut skipped = Vec::new();
            let m = mesh_io::read_gltf_noting(path, room, &mut skipped)?;
            summary.not_surfaces.extend(skipped.into_iter().map(|s| format!("{file}: {s}")));
            m
        }
        "ifc" => {
            return Err(PlantError::at(
                Location::file(path),
                "IFC is not read by liftplan: export the model from your BIM tool as glTF (.glb) or OBJ and put that in plant/",
            ));
        }
        other => {
            return Err(PlantError::at(
                Location::file(path),
                format!("unknown plant file type .{other} (expected {})", EXTS[..6].join(", ")),
            ));
        }
    };
    if let ("obj" | "ply" | "stl", Some(unit), Some(up)) = (ext.as_str(), s.unit, s.up_axis) {
        summary.meshes_read_as = Some(format!("in {}, {} up", unit.name(), if up == UpAxis::Y { "Y" } else { "Z" }));
        summary.unitless_mesh_files += 1;
    }
    if ext != "rvm" && m.triangles.is_empty() {
        // A mesh file that makes no surface at all (a point cloud saved as PLY,
        // a model of lines): nothing of it is an obstacle, which the signer
        // must read.
        summary.not_surfaces.push(format!("{file}: no faces at all"));
    }
    if ext != "rvm" {
        summary.groups += m.groups.len();
        // Selection applies to mesh objects too.
        let m = select_mesh(m, s, summary);
        return Ok(m);
    }
    Ok(m)
}

fn select_mesh(m: TriMesh, s: &Settings, summary: &mut Summary) -> TriMesh {
    let keep: Vec<bool> = m
        .groups
        .iter()
        .map(|g| {
            summary.seen_groups.push(g.clone());
            let inc = s.include.is_empty() || s.include.iter().any(|p| glob(p, g));
            let exc = s.exclude.iter().any(|p| glob(p, g));
            if exc {
                summary.excluded_groups.push(g.clone());
            }
            inc && !exc
        })
        .collect();
    // Where each excluded group stands: its triangles' corners, in one pass
    // over the triangles whatever the number of groups.
    let slot: Vec<Option<usize>> = m
        .groups
        .iter()
        .scan(0, |n, g| {
            Some(s.exclude.iter().any(|p| glob(p, g)).then(|| {
                *n += 1;
                *n - 1
            }))
        })
        .collect();
    let excluded = slot.iter().flatten().count();
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); excluded];
    if excluded > 0 {
        // Each group's connected pieces (triangles that share vertices) are
        // its parts: a scaffold's tubes, the two beams of an L.
        let mut parent: Vec<u32> = (0..m.vertices.len() as u32).collect();
        fn root(parent: &mut [u32], mut v: u32) -> u32 {
            while parent[v as usize] != v {
                parent[v as usize] = parent[parent[v as usize] as usize];
                v = parent[v as usize];
            }
            v
        }
        let of_excluded = |p: &u32| slot[m.parts[*p as usize].group as usize];
        for (t, _) in m.triangles.iter().zip(&m.part_of).filter(|(_, p)| of_excluded(p).is_some()) {
            for &v in &t[1..] {
                let (a, b) = (root(&mut parent, t[0]), root(&mut parent, v));
                if a != b {
                    parent[b as usize] = a;
                }
            }
        }
        // Each vertex once per group (most are shared by several triangles):
        // no more points than the mesh has vertices, whatever is left out.
        // (Slots as u32 beside the pieces' u32 parents: 8 bytes a vertex.)
        let mut last_slot = vec![u32::MAX; m.vertices.len()];
        for (t, p) in m.triangles.iter().zip(&m.part_of) {
            if let Some(k) = of_excluded(p) {
                for &v in t {
                    if std::mem::replace(&mut last_slot[v as usize], k as u32) != k as u32 {
                        members[k].push(v);
                    }
                }
            }
        }
        let mut by_piece: Vec<(u32, u32)> = Vec::new();
        let names = m.groups.iter().zip(&slot).filter(|(_, k)| k.is_some()).map(|(g, _)| g.clone());
        for (name, vertices) in names.zip(members) {
            by_piece.clear();
            by_piece.extend(vertices.iter().map(|&v| (root(&mut parent, v), v)));
            by_piece.sort_unstable();
            let points = by_piece.iter().map(|&(_, v)| m.vertices[v as usize]).collect();
            let ends =
                (1..=by_piece.len()).filter(|&i| i == by_piece.len() || by_piece[i].0 != by_piece[i - 1].0).collect();
            summary.excluded_points.push((name, points, ends));
        }
    }
    if keep.iter().all(|k| *k) {
        return m;
    }
    keep_groups(&m, &keep)
}

/// The parts of `m` whose group `keep` says to keep, copied part by part,
/// each with the vertices it uses in their order (what adding each part with
/// the whole vertex array and compacting gives; the tests keep that as the
/// reference). Asking the whole mesh for each part's triangles, and copying
/// every vertex per part, cost parts x (triangles + vertices): 5,000 OBJ
/// objects took 3.3 s, and 20,000 ran out of memory.
fn keep_groups(m: &TriMesh, keep: &[bool]) -> TriMesh {
    let mut first = vec![0usize; m.parts.len() + 1];
    for &p in &m.part_of {
        first[p as usize + 1] += 1;
    }
    for p in 0..m.parts.len() {
        first[p + 1] += first[p];
    }
    let mut by_part = vec![0usize; m.triangles.len()];
    let mut next = first.clone();
    for (t, &p) in m.part_of.iter().enumerate() {
        by_part[next[p as usize]] = t;
        next[p as usize] += 1;
    }
    let mut out = TriMesh::default();
    let mut index = GroupIndex::of(&out);
    let mut local = vec![0u32; m.vertices.len()];
    let (mut used, mut verts, mut tris) = (Vec::new(), Vec::new(), Vec::new());
    for (pi, part) in m.parts.iter().enumerate() {
        if !keep[part.group as usize] {
            continue;
        }
        let g = index.id(&mut out, &m.groups[part.group as usize]);
        let triangles = &by_part[first[pi]..first[pi + 1]];
        used.clear();
        used.extend(triangles.iter().flat_map(|&t| m.triangles[t]));
        used.sort_unstable();
        used.dedup();
        verts.clear();
        for (k, &v) in used.iter().enumerate() {
            local[v as usize] = k as u32;
            verts.push(m.vertices[v as usize]);
        }
        tris.clear();
        tris.extend(triangles.iter().map(|&t| m.triangles[t].map(|v| local[v as usize])));
        out.add_part(g, part.convex_solid, &verts, &tris);
    }
    out
}

/// Runs the stage on `inputs`, writing into `out_dir`; plant.json names the
/// files relative to `root` (the project folder) where given.
pub fn run(
    inputs: &[PathBuf],
    s: &Settings,
    out_dir: &Path,
    root: Option<&Path>,
    progress: &(dyn Fn(&str, u64, u64) + Sync),
) -> Result<Summary> {
    s.check().map_err(PlantError::Settings)?;
    let mut summary = Summary { tolerance_m: s.tolerance, ..Default::default() };
    let mut mesh = TriMesh::default();
    let mut groups = GroupIndex::of(&mesh);
    for (k, p) in inputs.iter().enumerate() {
        progress(
            &format!("read {}", p.file_name().map(|n| n.to_string_lossy()).unwrap_or_default()),
            k as u64,
            inputs.len() as u64,
        );
        let m = read_file(p, s, &mut summary)?;
        mesh.append_with(&m, &mut groups);
        summary.files.push(liftplan_core::location::shown(p, root));
    }
    progress("read", inputs.len() as u64, inputs.len() as u64);
    // A selection pattern that matches no group is most often a typo. An
    // include's would leave out of the obstacles what it was meant to keep
    // (with every include a typo, the whole model): refused. An exclude's
    // leaves in what it was meant to leave out, which errs on the safe
    // side: said.
    let unmatched = |patterns: &[String]| -> Vec<String> {
        patterns
            .iter()
            .filter(|p| !summary.seen_groups.iter().any(|g| glob(p, g)))
            .map(|p| match nearest_name(p, &summary.seen_groups) {
                Some(n) => format!("'{p}' (is it '{}'?)", liftplan_core::mesh::group_name_kept(n)),
                None => format!("'{p}'"),
            })
            .collect()
    };
    let include_unmatched = unmatched(&s.include);
    if !include_unmatched.is_empty() && !summary.seen_groups.is_empty() {
        return Err(PlantError::Settings(format!(
            "include {} matches no group of the model: what it was meant to keep would be no obstacle to any lift; correct it (the model's groups are named like {})",
            include_unmatched.join(", "),
            first_five(&summary.seen_groups)
        )));
    }
    summary.exclude_unmatched = unmatched(&s.exclude).into_iter().map(|p| format!("exclude {p}")).collect();
    let no_attributes =
        if summary.attribute_files == 0 { " (no RVM file has an .att attribute file beside it)" } else { "" };
    for rule in s.exclude_where.iter().filter(|r| !summary.exclude_where_matched.contains(*r)) {
        summary.exclude_unmatched.push(format!("exclude_where '{rule}'{no_attributes}"));
    }
    // Names are matched above whole; kept, for the words of later stages,
    // to their first MAX_GROUP_NAME_CHARS characters and a tag of the whole.
    summary.names_shortened = keep_group_names(&mut mesh.groups) + keep_group_names(&mut summary.excluded_groups);
    let pose = liftplan_core::frame::pose_xyz_yaw(
        s.translate_m[0],
        s.translate_m[1],
        s.translate_m[2],
        s.rotate_z_deg.to_radians(),
    );
    mesh.transform(&pose);
    // One box per name, over every file that has it, placed as the mesh is,
    // with its parts' boxes while there are not too many; grouped by the
    // whole name (two groups whose names agree in their first
    // MAX_GROUP_NAME_CHARS characters are two boxes), named as kept.
    let mut by_name: BTreeMap<String, (Vec<[f64; 3]>, Vec<usize>)> = BTreeMap::new();
    for (name, points, ends) in std::mem::take(&mut summary.excluded_points) {
        let (all, all_ends) = by_name.entry(name).or_default();
        let before = all.len();
        all_ends.extend(ends.iter().map(|e| before + e));
        all.extend(points.into_iter().map(|p| {
            let q = pose * liftplan_core::frame::Point3::from(p);
            [q.x, q.y, q.z]
        }));
    }
    let mut parts_left = liftplan_core::mesh::MAX_MODEL_BOX_PARTS;
    summary.excluded_boxes = by_name
        .iter()
        .filter_map(|(name, (points, ends))| {
            let name = liftplan_core::mesh::group_name_kept(name);
            let mut b = liftplan_core::mesh::ModelBox::around(&name, points)?;
            if ends.len() > 1 && ends.len() <= parts_left {
                let starts = std::iter::once(0).chain(ends.iter().copied());
                b.parts = starts
                    .zip(ends)
                    .filter_map(|(from, &to)| liftplan_core::mesh::ModelBox::around(&name, &points[from..to]))
                    .collect();
                parts_left -= ends.len();
            }
            Some(b)
        })
        .collect();
    summary.triangles = mesh.triangle_count();
    summary.vertices = mesh.vertices.len();
    let bb: Aabb = mesh.bbox();
    summary.bbox = if bb.is_empty() { [0.0; 6] } else { bb.to_array() };
    summary.max_error_m = s.tolerance;
    std::fs::create_dir_all(out_dir).map_err(|e| PlantError::Io(Location::file(out_dir), e))?;
    mesh.write_artifact(&out_dir.join("plant.mesh"))
        .map_err(|e| PlantError::at(Location::file(out_dir.join("plant.mesh")), e.to_string()))?;
    mesh.write_ply(&out_dir.join("plant.ply"))
        .map_err(|e| PlantError::Io(Location::file(out_dir.join("plant.ply")), e))?;
    let json = serde_json::to_string_pretty(&summary).unwrap_or_default();
    liftplan_core::artifact::write_atomic(&out_dir.join("plant.json"), json.as_bytes())
        .map_err(|e| PlantError::Io(Location::file(out_dir.join("plant.json")), e))?;
    Ok(summary)
}

/// `liftplan inspect` of a plant file.
pub fn inspect(path: &Path, s: &Settings) -> Result<serde_json::Value> {
    let mut summary = Summary { tolerance_m: s.tolerance, ..Default::default() };
    // Where the settings do not say them, an OBJ/PLY/STL file's own numbers.
    let own = Settings { unit: s.unit.or(Some(LengthUnit::M)), up_axis: s.up_axis.or(Some(UpAxis::Z)), ..s.clone() };
    let m = read_file(path, &own, &mut summary)?;
    let bb = m.bbox();
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let mut v = serde_json::json!({
        "kind": "plant",
        "format": ext,
        "file": path.display().to_string(),
        "groups": summary.groups,
        "primitives": summary.primitives,
        "triangles": m.triangle_count(),
        "vertices": m.vertices.len(),
        "bbox": if bb.is_empty() { serde_json::Value::Null } else { serde_json::json!(bb.to_array()) },
        "tolerance_m": s.tolerance,
    });
    if matches!(ext.as_str(), "obj" | "ply" | "stl") && (s.unit.is_none() || s.up_axis.is_none()) {
        v["coordinates"] = serde_json::json!(
            "the file's own numbers, Z taken as up: an OBJ, PLY or STL file states no unit or up axis"
        );
    }
    if ext == "rvm" {
        let f = rvm::read(path)?;
        v["model"] = serde_json::json!(f.model);
        v["project"] = serde_json::json!(f.project);
        v["info"] = serde_json::json!(f.info);
        v["attributes_file"] = serde_json::json!(att::beside(path).map(|p| p.display().to_string()));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::mesh::MeshPart;
    use rvm::{Group, Primitive, Role, RvmFile, Shape};

    /// How the stage kept groups before `keep_groups`: each kept part added
    /// with the whole vertex array and its triangles picked from the whole
    /// mesh, then unused vertices dropped.
    fn keep_groups_part_by_part(m: &TriMesh, keep: &[bool]) -> TriMesh {
        let mut out = TriMesh::default();
        for (pi, part) in m.parts.iter().enumerate() {
            if !keep[part.group as usize] {
                continue;
            }
            let tris: Vec<[u32; 3]> =
                m.triangles.iter().zip(&m.part_of).filter(|(_, p)| **p as usize == pi).map(|(t, _)| *t).collect();
            let g = out.group_id(&m.groups[part.group as usize]);
            out.add_part(g, part.convex_solid, &m.vertices, &tris);
        }
        out.compact();
        out
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(500))]
        /// Random meshes whose parts share vertices, leave some unused, have
        /// no triangles or interleave their triangles, in groups of repeated
        /// names: `keep_groups` gives the reference's mesh exactly.
        #[test]
        fn keeping_groups_matches_the_part_by_part_reference(
            vertex_count in 1usize..12,
            names in proptest::collection::vec(0u8..4, 1..6),
            parts in proptest::collection::vec((0usize..6, proptest::bool::ANY), 1..8),
            triangles in proptest::collection::vec((0usize..8, [0u32..12, 0u32..12, 0u32..12]), 0..40),
            keep in proptest::collection::vec(proptest::bool::ANY, 6),
        ) {
            let mut m = TriMesh {
                vertices: (0..vertex_count).map(|i| [i as f64, (i * i) as f64, 0.5]).collect(),
                groups: names.iter().map(|n| format!("G{n}")).collect(),
                ..Default::default()
            };
            for &(g, convex_solid) in &parts {
                m.parts.push(MeshPart { group: (g % names.len()) as u32, convex_solid });
            }
            for &(p, t) in &triangles {
                m.triangles.push(t.map(|v| v % vertex_count as u32));
                m.part_of.push((p % parts.len()) as u32);
            }
            let keep = &keep[..names.len()];
            proptest::prop_assert_eq!(keep_groups(&m, keep), keep_groups_part_by_part(&m, keep));
        }
    }

    /// An RVM file of `n` circular tori in group /ELBOWS, `scale` times their
    /// size in metres, written and read back as the stage reads it.
    fn tori_file(dir: &Path, n: usize, scale: f32) -> PathBuf {
        let torus = Primitive {
            role: Role::Primitive,
            matrix: [scale, 0.0, 0.0, 0.0, scale, 0.0, 0.0, 0.0, scale, 0.0, 0.0, 0.0],
            bbox_local: [-2.0, -2.0, -0.5, 2.0, 2.0, 0.5],
            shape: Shape::CircularTorus { offset: 1.5, radius: 0.5, angle: 6.0 },
            offset: 0,
        };
        let group = Group { name: "/ELBOWS".into(), primitives: vec![torus; n], ..Default::default() };
        let path = dir.join("plant.rvm");
        std::fs::write(&path, rvm::write(&RvmFile { groups: vec![group], ..Default::default() })).unwrap();
        path
    }

    /// A selection pattern that matches no group is a typo: an include's
    /// would leave out of the obstacles what it was meant to keep (all of
    /// the model here, which was planned with as nothing), so it is
    /// refused; an exclude's leaves in what it was meant to leave out, and
    /// is said, with the group it most likely meant.
    #[test]
    fn selection_patterns_that_match_nothing_are_named() {
        let d = tempfile::tempdir().unwrap();
        let path = tori_file(d.path(), 1, 1.0);
        let out = d.path().join("out");
        let run_with = |s: Settings| run(std::slice::from_ref(&path), &s, &out, None, &|_, _, _| {});
        let e = run_with(Settings { include: vec!["/ELBOW".into(), "/ELB*".into()], ..Default::default() })
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("include '/ELBOW' (is it '/ELBOWS'?) matches no group of the model: what it was meant to keep would be no obstacle"),
            "{e}"
        );
        assert!(!e.contains("'/ELB*'") && e.contains("named like /ELBOWS"), "{e}");
        let summary =
            run_with(Settings { exclude: vec!["/ELBOWZ".into(), "/PUMP-9".into()], ..Default::default() }).unwrap();
        assert!(summary.triangles > 0);
        let lines = summary.lines().join("\n");
        assert!(
            lines
                .contains("[plant] exclude '/ELBOWZ' (is it '/ELBOWS'?) matches no group: NOTHING WAS LEFT OUT for it"),
            "{lines}"
        );
        assert!(lines.contains("[plant] exclude '/PUMP-9' matches no group"), "{lines}");
        let summary = run_with(Settings { exclude: vec!["/elbows".into()], ..Default::default() }).unwrap();
        assert!(summary.exclude_unmatched.is_empty() && summary.triangles == 0, "{summary:?}");
    }

    /// `[plant] exclude_where` leaves out the groups whose attributes (the
    /// .att file beside the RVM) meet a rule; a rule that none meets is
    /// said like an unmatched exclude (it was not: a typo in it left in
    /// what it was meant to leave out, without a word), and so is every
    /// rule where no attribute file was read.
    #[test]
    fn exclude_where_rules_that_meet_nothing_are_named() {
        let d = tempfile::tempdir().unwrap();
        let path = tori_file(d.path(), 1, 1.0);
        let out = d.path().join("out");
        let run_with = |exclude: &[&str], rules: &[&str]| {
            let s = Settings {
                exclude: exclude.iter().map(|e| e.to_string()).collect(),
                exclude_where: rules.iter().map(|r| r.to_string()).collect(),
                ..Default::default()
            };
            run(std::slice::from_ref(&path), &s, &out, None, &|_, _, _| {}).unwrap()
        };
        let said = |summary: &Summary| summary.lines().join("\n");
        let without = run_with(&[], &["Purpose=TEMP*"]);
        assert!(without.triangles > 0);
        assert!(
            said(&without).contains("[plant] exclude_where 'Purpose=TEMP*' (no RVM file has an .att attribute file beside it) matches no group: NOTHING WAS LEFT OUT for it"),
            "{}",
            said(&without)
        );
        std::fs::write(
            path.with_extension("att"),
            "CADC_Attributes_File v1.0 , start: NEW , end: END\nNEW /ELBOWS\n Purpose:= TEMPORARY\nEND\n",
        )
        .unwrap();
        let left_out = run_with(&[], &["Purpose=TEMP*"]);
        assert!(left_out.triangles == 0 && left_out.excluded_groups == ["/ELBOWS"], "{left_out:?}");
        assert!(left_out.exclude_unmatched.is_empty(), "{left_out:?}");
        let typo = run_with(&[], &["Purpose=TMP*", "Purpose=TEMP*"]);
        assert_eq!(typo.exclude_unmatched, ["exclude_where 'Purpose=TMP*'"]);
        assert!(said(&typo).contains("[plant] exclude_where 'Purpose=TMP*' matches no group"), "{}", said(&typo));
        // Met by a group an exclude pattern left out first: met all the same.
        let both = run_with(&["/ELBOWS"], &["Purpose=TEMP*"]);
        assert!(both.exclude_unmatched.is_empty(), "{both:?}");
        // The attribute file as exports are delivered: its extension in
        // capitals, or renamed .txt (a .txt that is no attribute file is
        // not taken for one).
        let att = std::fs::read(path.with_extension("att")).unwrap();
        std::fs::remove_file(path.with_extension("att")).unwrap();
        std::fs::write(path.with_extension("txt"), "Model delivered 2026-03-02\n").unwrap();
        assert_eq!(run_with(&[], &["Purpose=TEMP*"]).attribute_files, 0);
        for renamed in ["ATT", "txt"] {
            std::fs::write(path.with_extension(renamed), &att).unwrap();
            let left_out = run_with(&[], &["Purpose=TEMP*"]);
            assert!(
                left_out.excluded_groups == ["/ELBOWS"] && left_out.attribute_files == 1,
                "{renamed}: {left_out:?}"
            );
            std::fs::remove_file(path.with_extension(renamed)).unwrap();
        }
    }

    /// A group left out of the model is kept as the box around it, placed as
    /// the mesh is ([plant] translate_m, rotate_z_deg), for the planner to
    /// compare with a lift's set position: its children's primitives
    /// included, whichever way the model turns it; an OBJ object likewise.
    #[test]
    fn excluded_groups_are_boxed_where_they_stand() {
        let d = tempfile::tempdir().unwrap();
        // A 4 x 1 x 1 m box turned 30° about Z at (5, 6, 1), in a child
        // group of the one excluded, and a 1 m cube beside it in the parent.
        let (c, s30) = (30f32.to_radians().cos(), 30f32.to_radians().sin());
        let turned = Primitive {
            role: Role::Primitive,
            matrix: [c, s30, 0.0, -s30, c, 0.0, 0.0, 0.0, 1.0, 5.0, 6.0, 1.0],
            bbox_local: [-2.0, -0.5, -0.5, 2.0, 0.5, 0.5],
            shape: Shape::Box { lengths: [4.0, 1.0, 1.0] },
            offset: 0,
        };
        let cube = Primitive {
            matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 20.0, 0.0, 0.5],
            bbox_local: [-0.5, -0.5, -0.5, 0.5, 0.5, 0.5],
            shape: Shape::Box { lengths: [1.0, 1.0, 1.0] },
            ..turned.clone()
        };
        let vessel = Group { name: "/V-1/SHELL".into(), primitives: vec![turned], ..Default::default() };
        let file = RvmFile {
            groups: vec![
                Group { name: "/V-1".into(), children: vec![vessel], ..Default::default() },
                Group { name: "/PUMP".into(), primitives: vec![cube], ..Default::default() },
            ],
            ..Default::default()
        };
        let path = d.path().join("plant.rvm");
        std::fs::write(&path, rvm::write(&file)).unwrap();
        let s = Settings {
            exclude: vec!["/V-1".into()],
            translate_m: [-1.0, -2.0, 0.5],
            rotate_z_deg: 90.0,
            ..Default::default()
        };
        let summary = run(std::slice::from_ref(&path), &s, &d.path().join("out"), None, &|_, _, _| {}).unwrap();
        assert_eq!(summary.excluded_groups, ["/V-1"]);
        let [b] = summary.excluded_boxes.as_slice() else { panic!("{:?}", summary.excluded_boxes) };
        // Turned 90° about the model's origin, then moved: (5, 6, 1) ->
        // (-6, 5, 1) -> (-7, 3, 1.5); the long side at 30° + 90°.
        assert_eq!(b.name, "/V-1");
        let near = |a: [f64; 3], e: [f64; 3]| (0..3).all(|i| (a[i] - e[i]).abs() < 1e-5);
        assert!(near(b.center_m, [-7.0, 3.0, 1.5]) && near(b.half_m, [2.0, 0.5, 0.5]), "{b:?}");
        assert!((b.yaw_deg - (-60.0)).abs() < 1e-4, "{b:?}");
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(d.path().join("out/plant.json")).unwrap()).unwrap();
        assert_eq!(json["excluded_boxes"][0]["name"], "/V-1");
        // An OBJ object left out is boxed from its vertices.
        let obj = d.path().join("skid.obj");
        std::fs::write(
            &obj,
            "o SKID\nv 0 0 0\nv 3 0 0\nv 3 2 0\nv 0 2 1\nf 1 2 3\nf 1 3 4\no KEEP\nv 9 9 0\nv 10 9 0\nv 10 10 0\nf 5 6 7\n",
        )
        .unwrap();
        let s = Settings {
            exclude: vec!["SKID".into()],
            unit: Some(LengthUnit::M),
            up_axis: Some(UpAxis::Z),
            ..Default::default()
        };
        let summary = run(&[obj], &s, &d.path().join("out2"), None, &|_, _, _| {}).unwrap();
        let [b] = summary.excluded_boxes.as_slice() else { panic!("{:?}", summary.excluded_boxes) };
        assert!(b.name == "SKID" && near(b.center_m, [1.5, 1.0, 0.5]) && near(b.half_m, [1.5, 1.0, 0.5]), "{b:?}");
        // Its vertices are no primitives: no parts, its own box.
        assert!(b.parts.is_empty() && b.boxes().len() == 1, "{b:?}");
    }

    /// A group name of thousands of characters (an RVM file can state any
    /// length) is matched by the selection whole and kept, in the mesh and
    /// among the groups left out, as its first 200 characters and a tag of
    /// the whole name (two agreeing in their first 200 read apart): the
    /// plan's pages name what a crane comes closest to by it, and said so.
    #[test]
    fn long_group_names_are_kept_short() {
        let d = tempfile::tempdir().unwrap();
        let cube = Primitive {
            role: Role::Primitive,
            matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.5],
            bbox_local: [-0.5, -0.5, -0.5, 0.5, 0.5, 0.5],
            shape: Shape::Box { lengths: [1.0, 1.0, 1.0] },
            offset: 0,
        };
        let (kept, left_out) = (format!("/RACK-{}", "A".repeat(5000)), format!("/SKID-{}", "B".repeat(300)));
        // Another left out, 5 m along, whose name agrees with it in its
        // first 200 characters: kept as other words, boxed on its own.
        let alike = format!("{left_out}B");
        let mut along = cube.clone();
        along.matrix[9] = 5.0;
        let file = RvmFile {
            groups: vec![
                Group { name: kept.clone(), primitives: vec![cube.clone()], ..Default::default() },
                Group { name: left_out.clone(), primitives: vec![cube], ..Default::default() },
                Group { name: alike.clone(), primitives: vec![along.clone()], ..Default::default() },
                // A terminal's escapes in a name: shown as U+FFFD, not
                // counted as shortened.
                Group { name: "/TANK\x1b]0;x\x07\n".into(), primitives: vec![along], ..Default::default() },
                Group { name: "/SHORT".into(), ..Default::default() },
            ],
            ..Default::default()
        };
        let path = d.path().join("plant.rvm");
        std::fs::write(&path, rvm::write(&file)).unwrap();
        // The pattern meets the name past its 200th character.
        let s = Settings { exclude: vec![format!("*{}", "B".repeat(250))], ..Default::default() };
        let summary = run(std::slice::from_ref(&path), &s, &d.path().join("out"), None, &|_, _, _| {}).unwrap();
        let short = |n: &str| {
            let tag = &blake3::hash(n.as_bytes()).to_hex()[..8];
            format!("{}... #{tag}", n.chars().take(200).collect::<String>())
        };
        assert!(summary.exclude_unmatched.is_empty(), "{:?}", summary.exclude_unmatched);
        assert_eq!(summary.excluded_groups, [short(&left_out), short(&alike)]);
        let boxes: Vec<(&str, f64)> = summary.excluded_boxes.iter().map(|b| (b.name.as_str(), b.center_m[0])).collect();
        assert_eq!(boxes, [(short(&left_out).as_str(), 0.0), (short(&alike).as_str(), 5.0)]);
        let mesh = TriMesh::read_artifact(&d.path().join("out/plant.mesh")).unwrap();
        assert_eq!(mesh.groups, [short(&kept), "/TANK\u{FFFD}]0;x\u{FFFD}\u{FFFD}".to_string()]);
        assert_eq!(summary.names_shortened, 3);
        assert!(
            summary
                .lines()
                .iter()
                .any(|l| l.starts_with("3 group names longer than 200 characters are kept as their first 200")),
            "{:?}",
            summary.lines()
        );
        assert!(summary.lines().iter().all(|l| l.chars().count() < 600), "{:?}", summary.lines());
    }

    /// An RVM group left out keeps its primitives' boxes as its parts (an
    /// L of two beams is not its empty corner), in plant.json too; an OBJ
    /// object its connected pieces' (one piece: its one box,
    /// `excluded_groups_are_boxed_where_they_stand`).
    #[test]
    fn an_excluded_groups_primitives_or_pieces_are_its_parts() {
        let d = tempfile::tempdir().unwrap();
        let beam = |x: f32, y: f32, lengths: [f32; 3]| Primitive {
            role: Role::Primitive,
            matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, x, y, 0.5],
            bbox_local: [-lengths[0] / 2.0, -lengths[1] / 2.0, -0.5, lengths[0] / 2.0, lengths[1] / 2.0, 0.5],
            shape: Shape::Box { lengths },
            offset: 0,
        };
        let l = Group {
            name: "/L".into(),
            primitives: vec![beam(5.0, 0.0, [10.0, 1.0, 1.0]), beam(0.0, 5.5, [1.0, 10.0, 1.0])],
            ..Default::default()
        };
        let file = RvmFile { groups: vec![l], ..Default::default() };
        let path = d.path().join("plant.rvm");
        std::fs::write(&path, rvm::write(&file)).unwrap();
        let s = Settings { exclude: vec!["/L".into()], ..Default::default() };
        let summary = run(std::slice::from_ref(&path), &s, &d.path().join("out"), None, &|_, _, _| {}).unwrap();
        let [b] = summary.excluded_boxes.as_slice() else { panic!("{:?}", summary.excluded_boxes) };
        let near = |a: [f64; 3], e: [f64; 3]| (0..3).all(|i| (a[i] - e[i]).abs() < 1e-5);
        let [x, y] = b.parts.as_slice() else { panic!("{b:?}") };
        assert!(near(x.center_m, [5.0, 0.0, 0.5]) && near(x.half_m, [5.0, 0.5, 0.5]), "{x:?}");
        assert!(near(y.center_m, [0.0, 5.5, 0.5]) && near(y.half_m, [5.0, 0.5, 0.5]), "{y:?}");
        // The empty corner is in the group's box, in none of its parts.
        let corner = liftplan_core::frame::Point3::new(3.0, 3.0, 0.5);
        let inside = |m: &liftplan_core::mesh::ModelBox| m.obb().contains(&corner);
        assert!(inside(b) && !b.boxes().iter().any(inside), "{b:?}");
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(d.path().join("out/plant.json")).unwrap()).unwrap();
        assert_eq!(json["excluded_boxes"][0]["parts"].as_array().map(Vec::len), Some(2));
        // The same L as an OBJ object of two separate quads: its connected
        // pieces are its parts.
        let obj = d.path().join("l.obj");
        std::fs::write(
            &obj,
            "o L\nv 0 -0.5 0\nv 10 -0.5 0\nv 10 0.5 1\nv 0 0.5 1\nf 1 2 3\nf 1 3 4\n\
             v -0.5 0.5 0\nv 0.5 0.5 0\nv 0.5 10.5 1\nv -0.5 10.5 1\nf 5 6 7\nf 5 7 8\n",
        )
        .unwrap();
        let s = Settings {
            exclude: vec!["L".into()],
            unit: Some(LengthUnit::M),
            up_axis: Some(UpAxis::Z),
            ..Default::default()
        };
        let summary = run(&[obj], &s, &d.path().join("out2"), None, &|_, _, _| {}).unwrap();
        let [b] = summary.excluded_boxes.as_slice() else { panic!("{:?}", summary.excluded_boxes) };
        let [x, y] = b.parts.as_slice() else { panic!("{b:?}") };
        assert!(near(x.center_m, [5.0, 0.0, 0.5]) && near(x.half_m, [5.0, 0.5, 0.5]), "{x:?}");
        assert!(near(y.center_m, [0.0, 5.5, 0.5]) && near(y.half_m, [5.0, 0.5, 0.5]), "{y:?}");
        assert!(inside(b) && !b.boxes().iter().any(inside), "{b:?}");
    }

    /// A model whose tessellation would pass the plant's triangle budget is
    /// refused before its triangles are made: here ten tori of a few hundred
    /// bytes each, scaled up 10^6 times, would make 336 million.
    #[test]
    fn a_model_too_large_to_hold_is_refused_before_it_is_tessellated() {
        let d = tempfile::tempdir().unwrap();
        let path = tori_file(d.path(), 10, 1e6);
        assert!(std::fs::metadata(&path).unwrap().len() < 10_000);
        let e = read_file(&path, &Settings::default(), &mut Summary::default()).unwrap_err().to_string();
        assert!(e.contains("plant.rvm") && e.contains("more than a plant may have (100000000)"), "{e}");
        assert!(e.contains("makes 335626200 triangles") && e.contains("a circular_torus of group /ELBOWS"), "{e}");
        assert!(e.contains("Raise [plant] tolerance"), "{e}");
    }

    /// Thousands of pipe ends on one spot are not compared pairwise (the
    /// square of their number): each end looks at CAP_CANDIDATES others at
    /// most and otherwise keeps its cap, which is always safe.
    #[test]
    fn a_crowd_of_ends_on_one_spot_is_not_compared_pairwise() {
        let cylinder = |z: f32| Primitive {
            role: Role::Primitive,
            matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, z],
            bbox_local: [-0.5, -0.5, -1.0, 0.5, 0.5, 1.0],
            shape: Shape::Cylinder { radius: 0.5, height: 2.0 },
            offset: 0,
        };
        // Two cylinders meeting at z = 1: both inner caps are hidden.
        let pair = [cylinder(0.0), cylinder(2.0)];
        let kept: Vec<(&Primitive, usize)> = pair.iter().map(|p| (p, 0)).collect();
        assert_eq!(caps_for(&kept), (vec![[true, false], [false, true]], 2));
        // 20,000 copies of the lower one, then the upper one: each top end of
        // the crowd would have to pass the other 19,999 (facing the same way)
        // to reach the upper cylinder's end. It stops at CAP_CANDIDATES and
        // keeps its cap; the upper cylinder's end meets a crowd end at once.
        let mut crowd: Vec<Primitive> = (0..20_000).map(|_| cylinder(0.0)).collect();
        crowd.push(cylinder(2.0));
        let kept: Vec<(&Primitive, usize)> = crowd.iter().map(|p| (p, 0)).collect();
        let (caps, culled) = caps_for(&kept);
        assert_eq!(culled, 1);
        assert_eq!(caps[20_000], [false, true]);
        assert!(caps[..20_000].iter().all(|c| *c == [true, true]));
    }

    /// What has no surface to keep is said in the stage's lines (the PDF's
    /// inputs page), not left to the console.
    #[test]
    fn what_is_not_an_obstacle_is_said() {
        let s =
            Summary { lines_skipped: 2, not_surfaces: vec!["site.glb: CABLE-1 (Lines)".into()], ..Default::default() };
        let lines = s.lines().join("\n");
        assert!(lines.contains("NOT AN OBSTACLE: 2 RVM line primitives"), "{lines}");
        assert!(lines.contains("NOT AN OBSTACLE: 1 items without a surface") && lines.contains("CABLE-1"));
        assert_eq!(Summary::default().lines().len(), 1);
    }

    /// A plant file that makes no surface at all (a point cloud saved as
    /// PLY) is said, not merged in as nothing.
    #[test]
    fn a_plant_file_without_faces_is_said() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("cloud.ply");
        let header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        std::fs::write(&path, format!("{header}0 0 0\n1 0 0\n0 1 0\n")).unwrap();
        let mut summary = Summary::default();
        let s = Settings { unit: Some(LengthUnit::M), up_axis: Some(UpAxis::Z), ..Default::default() };
        let m = read_file(&path, &s, &mut summary).unwrap();
        assert!(m.triangles.is_empty());
        let lines = summary.lines().join("\n");
        assert!(lines.contains("NOT AN OBSTACLE") && lines.contains("cloud.ply: no faces at all"), "{lines}");
    }

    /// An OBJ, PLY or STL file states neither its unit nor its up axis: it
    /// is refused, naming the file and what to set, until `[plant] unit`
    /// and `up_axis` say them (a model in Revit's feet read as metres puts
    /// every obstacle 3.28 times too far out; a Y-up model read as Z-up lies
    /// on its side), then read in them and the run's lines say so.
    /// `inspect` shows the file's own numbers.
    #[test]
    fn a_mesh_file_needs_its_unit_and_up_axis_said() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("part.obj");
        std::fs::write(&path, "v 0 0 0\nv 1000 0 0\nv 0 2000 0\nf 1 2 3\n").unwrap();
        let read = |unit, up_axis| {
            let mut summary = Summary::default();
            read_file(&path, &Settings { unit, up_axis, ..Default::default() }, &mut summary).map(|m| (m, summary))
        };
        let e = read(None, None).unwrap_err().to_string();
        assert!(e.contains("part.obj") && e.contains("[plant] unit") && e.contains("up_axis"), "{e}");
        let e = read(Some(LengthUnit::Mm), None).unwrap_err().to_string();
        assert!(e.contains("set [plant] up_axis") && !e.contains("unit ("), "{e}");
        let (m, summary) = read(Some(LengthUnit::Mm), Some(UpAxis::Y)).unwrap();
        let b = m.bbox().to_array();
        // Y up: the file's y (2000 mm) is the height.
        assert_eq!((b[3], b[5]), (1.0, 2.0), "{b:?}");
        let lines = summary.lines().join("\n");
        assert!(
            lines.contains("OBJ/PLY/STL coordinates in mm, Y up, as [plant] unit and up_axis say: 1 file"),
            "{lines}"
        );
        let shown = inspect(&path, &Settings::default()).unwrap();
        assert!(shown["coordinates"].as_str().unwrap().contains("own numbers"), "{shown}");
        assert_eq!(shown["bbox"][3], 1000.0, "{shown}");
    }

    /// A joint of two radii culls only the narrower end's cap, which the
    /// wider end's disk covers; the wider end keeps its cap, else the ring
    /// between them would be open. Ends of one radius, to the `f32` noise of
    /// a file, both cull theirs.
    #[test]
    fn a_cap_is_culled_only_where_the_other_end_covers_it() {
        let cylinder = |z: f32, radius: f32| Primitive {
            role: Role::Primitive,
            matrix: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, z],
            bbox_local: [-radius, -radius, -1.0, radius, radius, 1.0],
            shape: Shape::Cylinder { radius, height: 2.0 },
            offset: 0,
        };
        for (lower, upper, want) in [
            (0.5, 0.52, (vec![[true, false], [true, true]], 1)),
            (0.52, 0.5, (vec![[true, true], [false, true]], 1)),
            (0.5, 0.500_000_06, (vec![[true, false], [false, true]], 2)),
        ] {
            let pair = [cylinder(0.0, lower), cylinder(2.0, upper)];
            let kept: Vec<(&Primitive, usize)> = pair.iter().map(|p| (p, 0)).collect();
            assert_eq!(caps_for(&kept), want, "radii {lower} and {upper}");
        }
    }

    /// The budget counts the files read before: a model that fits the room
    /// left exactly is read, one triangle less room refuses it.
    #[test]
    fn the_triangle_budget_counts_earlier_files() {
        let d = tempfile::tempdir().unwrap();
        let path = tori_file(d.path(), 3, 1.0);
        let s = Settings::default();
        let m = read_file(&path, &s, &mut Summary::default()).unwrap();
        let n = m.triangle_count();
        assert!(n > 100, "{n}");
        let mut summary = Summary { triangles: MAX_TRIANGLES as usize - n, ..Default::default() };
        read_file(&path, &s, &mut summary).unwrap();
        assert_eq!(summary.triangles, MAX_TRIANGLES as usize);
        let mut summary = Summary { triangles: MAX_TRIANGLES as usize - n + 1, ..Default::default() };
        let e = read_file(&path, &s, &mut summary).unwrap_err().to_string();
        assert!(e.contains("with the plant files read before it"), "{e}");
    }
}
