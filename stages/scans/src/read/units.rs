//! The unit a scan file states for its coordinates: a LAS/LAZ file's CRS
//! (GeoTIFF keys or WKT), E57's metres by its standard.
//!
//! A survey in US survey feet read as metres would put every obstacle 3.28
//! times farther away than it is, so a unit a file states is applied, and one
//! liftplan cannot apply (degrees of a geographic CRS, a unit it does not
//! know, geocentric axes) is refused. Files that state none are read in
//! `[scans] unit`. A CRS named only by an EPSG code does not state its unit:
//! liftplan holds no EPSG registry, so such a file is read in the unit the
//! project says, and refused where it says none (State Plane CRSs in US
//! feet are named this way as often as metric ones), except for a few
//! families whose codes are known to be in metres ([`metric_crs`]).
//!
//! What this module must not do: guess a unit from an EPSG code outside
//! those families, or read past the bytes it is given.

/// The unit a file states, as metres per coordinate unit, and where it says
/// so.
#[derive(Debug, Clone, PartialEq)]
pub struct StatedUnit {
    /// Metres per unit of x and y.
    pub horizontal_m: f64,
    /// Metres per unit of z.
    pub vertical_m: f64,
    /// The unit's name and where it was found, for the run's lines.
    pub what: String,
}

impl StatedUnit {
    pub fn metres(what: &str) -> StatedUnit {
        StatedUnit { horizontal_m: 1.0, vertical_m: 1.0, what: what.into() }
    }

    pub fn is_metres(&self) -> bool {
        self.horizontal_m == 1.0 && self.vertical_m == 1.0
    }
}

/// What a file says of its coordinates' unit.
#[derive(Debug, Clone, PartialEq)]
pub enum CrsUnit {
    /// Its CRS states the unit.
    Stated(StatedUnit),
    /// It names a CRS (`crs`: by an EPSG code, say, and where) whose unit
    /// it does not state: the project must say it. `heights` is the unit
    /// it states for heights, if it states one.
    Unstated { crs: String, heights: Option<(String, f64)> },
    /// It names no CRS at all.
    None,
}

/// Projected CRSs whose EPSG codes are known to be in metres, by family:
/// the name of `code`'s CRS if it is one of them. Each is a transverse
/// Mercator or national grid in metres by its definition.
pub fn metric_crs(code: u16) -> Option<String> {
    let zone = |first: u16, last: u16, zone_of_first: u16| {
        (first..=last).contains(&code).then(|| code - first + zone_of_first)
    };
    if let Some(z) = zone(32601, 32660, 1) {
        return Some(format!("WGS 84 / UTM zone {z}N"));
    }
    if let Some(z) = zone(32701, 32760, 1) {
        return Some(format!("WGS 84 / UTM zone {z}S"));
    }
    if let Some(z) = zone(26901, 26923, 1) {
        return Some(format!("NAD83 / UTM zone {z}N"));
    }
    if let Some(z) = zone(25828, 25838, 28) {
        return Some(format!("ETRS89 / UTM zone {z}N"));
    }
    if let Some(z) = zone(28348, 28358, 48) {
        return Some(format!("GDA94 / MGA zone {z}"));
    }
    if let Some(z) = zone(7846, 7859, 46) {
        return Some(format!("GDA2020 / MGA zone {z}"));
    }
    match code {
        27700 => Some("OSGB36 / British National Grid".into()),
        28992 => Some("Amersfoort / RD New".into()),
        2056 => Some("CH1903+ / LV95".into()),
        _ => None,
    }
}

/// GeoTIFF key ids (GeoTIFF 1.1, section 7).
const GT_MODEL_TYPE: u16 = 1024;
const GEODETIC_CRS: u16 = 2048;
const PROJECTED_CRS: u16 = 3072;
const PROJ_LINEAR_UNITS: u16 = 3076;
const VERTICAL_UNITS: u16 = 4099;
/// GTModelTypeGeoKey's values: projected, geographic 2D (degrees),
/// geocentric (earth-centred axes: z is not up).
const MODEL_PROJECTED: u16 = 1;
const MODEL_GEOGRAPHIC: u16 = 2;
const MODEL_GEOCENTRIC: u16 = 3;
/// The code GeoTIFF gives a user-defined CRS (its parameters in other keys).
const USER_DEFINED: u16 = 32767;

/// EPSG linear unit codes and metres per unit.
const LINEAR_UNITS: &[(u16, &str, f64)] = &[
    (9001, "metre", 1.0),
    (9002, "foot", 0.3048),
    (9003, "US survey foot", 1200.0 / 3937.0),
    (9005, "Clarke's foot", 0.3047972654),
    (9031, "German legal metre", 1.0000135965),
    (9036, "kilometre", 1000.0),
];

fn linear_unit(code: u16, key: &str) -> Result<(&'static str, f64), String> {
    LINEAR_UNITS
        .iter()
        .find(|u| u.0 == code)
        .map(|u| (u.1, u.2))
        .ok_or_else(|| format!("its GeoTIFF {key} is EPSG unit {code}, which liftplan does not convert (it takes metre 9001, foot 9002, US survey foot 9003, Clarke's foot 9005, German legal metre 9031, kilometre 9036); reproject the scan to metres or feet"))
}

/// The unit a GeoTIFF key directory (the `LASF_Projection` record 34735)
/// states.
pub fn from_geokeys(data: &[u8]) -> Result<CrsUnit, String> {
    let word = |k: usize| data.get(2 * k..2 * k + 2).map(|b| u16::from_le_bytes([b[0], b[1]]));
    let Some(n) = word(3) else {
        return Err(format!("its GeoTIFF key directory is {} bytes, shorter than its 8-byte header", data.len()));
    };
    if data.len() < 8 + 8 * n as usize {
        return Err(format!("its GeoTIFF key directory claims {n} keys but holds {} bytes", data.len()));
    }
    // Keys whose value is in the directory itself (location 0).
    let value = |id: u16| {
        (0..n as usize).find_map(|e| {
            let at = 4 + 4 * e;
            (word(at) == Some(id) && word(at + 1) == Some(0)).then(|| word(at + 3)).flatten()
        })
    };
    let model = value(GT_MODEL_TYPE);
    let projected = value(PROJECTED_CRS).is_some_and(|c| c != 0);
    // A geodetic CRS with no projection over it, whether or not the model
    // type says so, is in degrees.
    if model == Some(MODEL_GEOGRAPHIC)
        || (model != Some(MODEL_PROJECTED) && !projected && value(GEODETIC_CRS).is_some())
    {
        let crs = value(GEODETIC_CRS).map(|c| format!(" (EPSG:{c})")).unwrap_or_default();
        return Err(format!(
            "its CRS is geographic{crs}: coordinates in degrees; reproject the scan to a projected or local CRS in metres or feet"
        ));
    }
    if model == Some(MODEL_GEOCENTRIC) {
        return Err("its CRS is geocentric: earth-centred axes, whose z is not up; reproject the scan to a projected or local CRS".into());
    }
    let heights = value(VERTICAL_UNITS).map(|c| linear_unit(c, "VerticalUnitsGeoKey")).transpose()?;
    let code = value(PROJECTED_CRS).filter(|&c| c != 0 && c != USER_DEFINED);
    let crs = code.map(|c| format!("EPSG:{c}, ")).unwrap_or_default();
    let (name, h, whence) = match value(PROJ_LINEAR_UNITS) {
        Some(u) => {
            let (name, h) = linear_unit(u, "ProjLinearUnitsGeoKey")?;
            (name, h, format!("{crs}GeoTIFF keys"))
        }
        None => match code.map(|c| (c, metric_crs(c))) {
            Some((c, Some(known))) => {
                ("metre", 1.0, format!("EPSG:{c}, {known}, metres by its definition; GeoTIFF keys"))
            }
            Some((c, None)) => {
                let heights = heights.map(|(n, v)| (n.to_string(), v));
                return Ok(CrsUnit::Unstated { crs: format!("EPSG:{c}, named by its code only"), heights });
            }
            None if model == Some(MODEL_PROJECTED) || projected || heights.is_some() => {
                let heights = heights.map(|(n, v)| (n.to_string(), v));
                return Ok(CrsUnit::Unstated {
                    crs: "a CRS with no code and no ProjLinearUnitsGeoKey".into(),
                    heights,
                });
            }
            None => return Ok(CrsUnit::None),
        },
    };
    let (v, vertical) = match heights {
        Some((vname, v)) => (v, format!("heights in {vname}")),
        None => (h, "heights taken in the same unit, as it states none for them".to_string()),
    };
    Ok(CrsUnit::Stated(StatedUnit { horizontal_m: h, vertical_m: v, what: format!("{name} ({whence}; {vertical})") }))
}

/// The most a WKT CRS may hold (bytes) and nest (brackets): real ones are a
/// few kilobytes and a dozen deep.
const MAX_WKT_BYTES: usize = 1 << 20;
const MAX_WKT_DEPTH: usize = 64;

/// A WKT node: its keyword and, in order, its quoted or bare values and its
/// child nodes.
#[derive(Debug, Default)]
struct Node {
    keyword: String,
    values: Vec<String>,
    children: Vec<Node>,
}

impl Node {
    fn child(&self, keywords: &[&str]) -> Option<&Node> {
        self.children.iter().find(|c| keywords.iter().any(|k| c.keyword.eq_ignore_ascii_case(k)))
    }
}

/// Parses WKT (1 or 2) into its node tree.
fn parse_wkt(text: &str) -> Result<Node, String> {
    if text.len() > MAX_WKT_BYTES {
        return Err(format!("its WKT CRS is {} bytes, more than {MAX_WKT_BYTES}", text.len()));
    }
    let mut stack: Vec<Node> = vec![Node::default()];
    let mut word = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                // A quoted value; "" inside stands for one quote.
                let mut s = String::new();
                loop {
                    match chars.next() {
                        Some('"') if chars.peek() == Some(&'"') => {
                            chars.next();
                            s.push('"');
                        }
                        Some('"') => break,
                        Some(ch) => s.push(ch),
                        None => return Err("its WKT CRS ends inside a quoted name".into()),
                    }
                }
                if let Some(n) = stack.last_mut() {
                    n.values.push(s);
                }
            }
            '[' | '(' => {
                if stack.len() > MAX_WKT_DEPTH {
                    return Err(format!("its WKT CRS nests deeper than {MAX_WKT_DEPTH}"));
                }
                stack.push(Node { keyword: std::mem::take(&mut word).trim().to_string(), ..Node::default() });
            }
            ']' | ')' => {
                let w = std::mem::take(&mut word);
                let mut done =
                    stack.pop().filter(|_| !stack.is_empty()).ok_or("its WKT CRS closes a bracket it never opened")?;
                if !w.trim().is_empty() {
                    done.values.push(w.trim().to_string());
                }
                if let Some(n) = stack.last_mut() {
                    n.children.push(done);
                }
            }
            ',' => {
                let w = std::mem::take(&mut word);
                if !w.trim().is_empty()
                    && let Some(n) = stack.last_mut()
                {
                    n.values.push(w.trim().to_string());
                }
            }
            _ => word.push(c),
        }
    }
    let mut root = stack.pop().filter(|_| stack.is_empty()).ok_or("its WKT CRS leaves a bracket open")?;
    match root.children.len() {
        1 => Ok(root.children.remove(0)),
        0 => Err("its WKT CRS holds no CRS".into()),
        _ => Err("its WKT CRS holds more than one CRS".into()),
    }
}

/// A unit node's name and metres per unit.
fn unit_of(n: &Node) -> Result<(String, f64), String> {
    let name = n.values.first().cloned().unwrap_or_default();
    let factor: f64 = n
        .values
        .get(1)
        .and_then(|v| v.parse().ok())
        .ok_or_else(|| format!("its WKT CRS's unit \"{name}\" has no conversion factor"))?;
    if !(factor.is_finite() && (1e-4..=1e4).contains(&factor)) {
        return Err(format!("its WKT CRS's unit \"{name}\" has the conversion factor {factor}, not a length unit"));
    }
    Ok((name, factor))
}

/// The length unit of a coordinate system node: its own UNIT / LENGTHUNIT,
/// else its axes' (WKT 2 may give the unit per axis).
fn length_unit(n: &Node) -> Result<Option<(String, f64)>, String> {
    if let Some(u) = n.child(&["LENGTHUNIT", "UNIT"]) {
        return unit_of(u).map(Some);
    }
    for axis in n.children.iter().filter(|c| c.keyword.eq_ignore_ascii_case("AXIS")) {
        if let Some(u) = axis.child(&["LENGTHUNIT", "UNIT"]) {
            return unit_of(u).map(Some);
        }
    }
    Ok(None)
}

const GEOGRAPHIC: &[&str] = &["GEOGCS", "GEOGCRS", "GEOGRAPHICCRS", "GEODCRS", "GEODETICCRS"];
const HORIZONTAL: &[&str] = &["PROJCS", "PROJCRS", "PROJECTEDCRS", "LOCAL_CS", "ENGCRS", "ENGINEERINGCRS"];
const VERTICAL: &[&str] = &["VERT_CS", "VERTCRS", "VERTICALCRS"];

/// The unit a WKT CRS (the `LASF_Projection` record 2112) states.
pub fn from_wkt(bytes: &[u8]) -> Result<CrsUnit, String> {
    let text = String::from_utf8_lossy(bytes);
    let text = text.trim_end_matches('\0').trim();
    if text.is_empty() {
        return Ok(CrsUnit::None);
    }
    let is = |n: &Node, kinds: &[&str]| kinds.iter().any(|k| n.keyword.eq_ignore_ascii_case(k));
    let mut root = parse_wkt(text)?;
    // A WKT 2 CRS with a transformation to another: the coordinates are in
    // its source CRS.
    while is(&root, &["BOUNDCRS"]) {
        let source = root.children.iter_mut().find(|c| is(c, &["SOURCECRS"]));
        match source.and_then(|s| (!s.children.is_empty()).then(|| s.children.remove(0))) {
            Some(crs) => root = crs,
            None => return Err("its WKT BOUNDCRS has no SOURCECRS".into()),
        }
    }
    let compound = is(&root, &["COMPD_CS", "COMPOUNDCRS"]);
    let horizontal =
        if compound { root.children.iter().find(|c| is(c, HORIZONTAL) || is(c, GEOGRAPHIC)) } else { Some(&root) };
    let vertical = if compound { root.children.iter().find(|c| is(c, VERTICAL)) } else { None };
    let vertical = vertical.map(length_unit).transpose()?.flatten();
    let named = |what: &str| {
        let name = root.values.first().map(|n| format!("\"{n}\"")).unwrap_or_else(|| "its WKT CRS".into());
        CrsUnit::Unstated { crs: format!("{name}, whose WKT {what}"), heights: vertical.clone() }
    };
    let Some(h) = horizontal else { return Ok(named("has no horizontal part")) };
    if is(h, &["GEOCCS"]) {
        return Err("its CRS is geocentric: earth-centred axes, whose z is not up; reproject the scan to a projected or local CRS".into());
    }
    if is(h, GEOGRAPHIC) {
        let name = h.values.first().cloned().unwrap_or_default();
        return Err(format!(
            "its CRS is geographic (\"{name}\"): coordinates in degrees; reproject the scan to a projected or local CRS in metres or feet"
        ));
    }
    if !is(h, HORIZONTAL) {
        return Err(format!("its WKT CRS is a {}, which liftplan does not read coordinates in", h.keyword));
    }
    let Some((hname, hf)) = length_unit(h)? else { return Ok(named("states no length unit")) };
    let (vf, vertical) = match vertical {
        Some((vname, vf)) => (vf, format!("heights in {vname}")),
        None => (hf, "heights taken in the same unit, as it states none for them".to_string()),
    };
    Ok(CrsUnit::Stated(StatedUnit { horizontal_m: hf, vertical_m: vf, what: format!("{hname} (WKT CRS; {vertical})") }))
}

/// A GeoTIFF key directory of `keys` (id, value), each held in the
/// directory itself.
#[cfg(test)]
pub(crate) fn geokeys(keys: &[(u16, u16)]) -> Vec<u8> {
    let mut w = vec![1u16, 1, 0, keys.len() as u16];
    for &(id, v) in keys {
        w.extend([id, 0, 1, v]);
    }
    w.iter().flat_map(|x| x.to_le_bytes()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn stated(u: Result<CrsUnit, String>) -> StatedUnit {
        match u {
            Ok(CrsUnit::Stated(s)) => s,
            other => panic!("not a stated unit: {other:?}"),
        }
    }

    #[test]
    fn geotiff_keys_state_feet_metres_or_nothing() {
        let us = stated(from_geokeys(&geokeys(&[(1024, 1), (3072, 2263), (3076, 9003), (4099, 9003)])));
        assert_eq!((us.horizontal_m, us.vertical_m), (1200.0 / 3937.0, 1200.0 / 3937.0));
        assert!(us.what.contains("US survey foot") && us.what.contains("EPSG:2263"), "{}", us.what);
        let m = stated(from_geokeys(&geokeys(&[(1024, 1), (3072, 32633), (3076, 9001)])));
        assert!(m.is_metres() && m.what.contains("same unit"), "{}", m.what);
        let mixed = stated(from_geokeys(&geokeys(&[(3076, 9002), (4099, 9001)])));
        assert_eq!((mixed.horizontal_m, mixed.vertical_m), (0.3048, 1.0));
        // Only an EPSG code: the unit is not stated, unless the code is of a
        // family in metres by definition.
        let unstated = |keys: &[(u16, u16)]| match from_geokeys(&geokeys(keys)) {
            Ok(CrsUnit::Unstated { crs, heights }) => (crs, heights),
            other => panic!("{keys:?}: {other:?}"),
        };
        let (crs, heights) = unstated(&[(1024, 1), (3072, 2263)]);
        assert!(crs.contains("EPSG:2263") && heights.is_none(), "{crs}");
        let (_, heights) = unstated(&[(1024, 1), (3072, 2263), (4099, 9003)]);
        assert_eq!(heights, Some(("US survey foot".to_string(), 1200.0 / 3937.0)));
        // User-defined with no unit key, or a projected model with no code.
        assert!(unstated(&[(1024, 1), (3072, 32767)]).0.contains("no code"));
        assert!(unstated(&[(1024, 1)]).0.contains("no code"));
        for (code, name) in [
            (32633, "WGS 84 / UTM zone 33N"),
            (32760, "WGS 84 / UTM zone 60S"),
            (26910, "NAD83 / UTM zone 10N"),
            (25832, "ETRS89 / UTM zone 32N"),
            (28355, "GDA94 / MGA zone 55"),
            (7856, "GDA2020 / MGA zone 56"),
            (27700, "OSGB36 / British National Grid"),
        ] {
            let m = stated(from_geokeys(&geokeys(&[(1024, 1), (3072, code)])));
            assert!(m.is_metres() && m.what.contains(name), "{code}: {}", m.what);
        }
        for not_metric in [32600, 32661, 26924, 2263, 2229, 6539, 3857] {
            assert_eq!(metric_crs(not_metric), None, "{not_metric}");
        }
        assert_eq!(from_geokeys(&geokeys(&[])).unwrap(), CrsUnit::None);
        // Geographic, whether the model type says so or only a geodetic CRS
        // with no projection is named.
        for keys in [&[(1024, 2), (2048, 4326)][..], &[(2048, 4326)]] {
            let e = from_geokeys(&geokeys(keys)).unwrap_err();
            assert!(e.contains("geographic") && e.contains("EPSG:4326"), "{e}");
        }
        let e = from_geokeys(&geokeys(&[(1024, 3), (3076, 9001)])).unwrap_err();
        assert!(e.contains("geocentric"), "{e}");
        let e = from_geokeys(&geokeys(&[(3076, 9014)])).unwrap_err();
        assert!(e.contains("9014"), "{e}");
        let e = from_geokeys(&geokeys(&[(3076, 9001)])[..12]).unwrap_err();
        assert!(e.contains("claims 1 keys but holds 12 bytes"), "{e}");
    }

    #[test]
    fn wkt_states_its_units() {
        let wkt1 = r#"COMPD_CS["NAD83 / New York Long Island (ftUS) + NAVD88 height (ftUS)",PROJCS["NAD83 / New York Long Island (ftUS)",GEOGCS["NAD83",DATUM["North_American_Datum_1983",SPHEROID["GRS 1980",6378137,298.257222101]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Lambert_Conformal_Conic_2SP"],PARAMETER["standard_parallel_1",41.0333333333333],UNIT["US survey foot",0.304800609601219,AUTHORITY["EPSG","9003"]],AXIS["Easting",EAST],AXIS["Northing",NORTH]],VERT_CS["NAVD88 height (ftUS)",VERT_DATUM["North American Vertical Datum 1988",2005],UNIT["US survey foot",0.304800609601219],AXIS["Gravity-related height",UP]]]"#;
        let u = stated(from_wkt(wkt1.as_bytes()));
        assert_eq!((u.horizontal_m, u.vertical_m), (0.304800609601219, 0.304800609601219));
        assert!(u.what.contains("US survey foot") && u.what.contains("heights in US survey foot"), "{}", u.what);
        let wkt2 = r#"PROJCRS["WGS 84 / UTM zone 33N",BASEGEOGCRS["WGS 84",DATUM["World Geodetic System 1984",ELLIPSOID["WGS 84",6378137,298.257223563,LENGTHUNIT["metre",1]]],ANGLEUNIT["degree",0.0174532925199433]],CONVERSION["UTM zone 33N",METHOD["Transverse Mercator"]],CS[Cartesian,2],AXIS["(E)",east,ORDER[1],LENGTHUNIT["metre",1]],AXIS["(N)",north,ORDER[2],LENGTHUNIT["metre",1]],ID["EPSG",32633]]"#;
        assert!(stated(from_wkt(wkt2.as_bytes())).is_metres());
        let bound = format!(
            r#"BOUNDCRS[SOURCECRS[{wkt2}],TARGETCRS[GEOGCRS["WGS 84",CS[ellipsoidal,2]]],ABRIDGEDTRANSFORMATION["x",METHOD["Geocentric translations"]]]"#
        );
        assert_eq!(stated(from_wkt(bound.replace("\"metre\",1", "\"foot\",0.3048").as_bytes())).horizontal_m, 0.3048);
        let e = from_wkt(br#"GEOGCS["WGS 84",DATUM["WGS_1984"],UNIT["degree",0.0174532925199433]]"#).unwrap_err();
        assert!(e.contains("geographic") && e.contains("degrees"), "{e}");
        assert_eq!(from_wkt(b"\0\0").unwrap(), CrsUnit::None);
        // A local CRS with no unit: named, its unit not stated.
        match from_wkt(br#"LOCAL_CS["site grid",LOCAL_DATUM["site",0]]"#).unwrap() {
            CrsUnit::Unstated { crs, .. } => {
                assert!(crs.contains("site grid") && crs.contains("no length unit"), "{crs}")
            }
            other => panic!("{other:?}"),
        }
        let e = from_wkt(br#"GEOCCS["WGS 84",DATUM["WGS_1984"],UNIT["metre",1]]"#).unwrap_err();
        assert!(e.contains("geocentric"), "{e}");
        for bad in [&b"PROJCS[\"x\""[..], b"PROJCS[\"x\"]]", b"PROJCS[\"x\",UNIT[\"foot\",zero]]"] {
            assert!(from_wkt(bad).is_err(), "{}", String::from_utf8_lossy(bad));
        }
        let deep = "PROJCS[".repeat(10_000);
        assert!(from_wkt(deep.as_bytes()).unwrap_err().contains("deeper"));
    }

    proptest! {
        /// Any bytes give a unit, none or an error: never a panic.
        #[test]
        fn any_crs_bytes_read_or_give_an_error(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
            let _ = from_geokeys(&bytes);
            let _ = from_wkt(&bytes);
        }

        /// Damaged copies of a real WKT read or give an error.
        #[test]
        fn damaged_wkt_reads_or_gives_an_error(at in 0usize..200, with in any::<u8>(), cut in 0usize..260) {
            let mut w = br#"PROJCS["NAD83 / x (ftUS)",GEOGCS["NAD83",UNIT["degree",0.0174532925199433]],UNIT["US survey foot",0.304800609601219],AXIS["Easting",EAST]]"#.to_vec();
            let at = at % w.len();
            w[at] = with;
            w.truncate(cut.min(w.len()));
            let _ = from_wkt(&w);
        }
    }
}
