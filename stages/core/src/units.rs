//! Unit conversions at the edges of the system.
//!
//! Inside liftplan everything is SI: metres, kilograms, radians, seconds. Degrees,
//! tonnes, feet and pounds exist only in project files, load charts, tables and the
//! PDF; these helpers are the only place that converts. Names carry the unit
//! (`radius_m`, `capacity_kg`, `swing_rad`) wherever a mix-up is possible.

pub const KG_PER_TONNE: f64 = 1000.0;
pub const KG_PER_LB: f64 = 0.453_592_37;
/// A US short ton (2000 lb), as "tons" appear in North American charts.
pub const KG_PER_SHORT_TON: f64 = 2000.0 * KG_PER_LB;
/// A kip is 1000 lb of force; load charts use it for 1000 lb of mass.
pub const KG_PER_KIP: f64 = 1000.0 * KG_PER_LB;
pub const M_PER_FT: f64 = 0.3048;
/// Standard gravity (m/s²): a mass's weight, for pad loads in kilonewtons
/// and the wind's push against a hanging load.
pub const G_M_S2: f64 = 9.806_65;

#[inline]
pub fn deg_to_rad(deg: f64) -> f64 {
    deg.to_radians()
}

#[inline]
pub fn rad_to_deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// A length unit found in a file header or a chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LengthUnit {
    M,
    Mm,
    Cm,
    Ft,
    In,
}

impl LengthUnit {
    pub fn to_m(self) -> f64 {
        match self {
            LengthUnit::M => 1.0,
            LengthUnit::Mm => 0.001,
            LengthUnit::Cm => 0.01,
            LengthUnit::Ft => M_PER_FT,
            LengthUnit::In => M_PER_FT / 12.0,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            LengthUnit::M => "m",
            LengthUnit::Mm => "mm",
            LengthUnit::Cm => "cm",
            LengthUnit::Ft => "ft",
            LengthUnit::In => "in",
        }
    }
}

/// A mass unit found in a load chart, or the force unit of a chart that
/// rates its capacities as the weight they may be (kilonewtons, as some
/// European charts do; decanewtons, as French ones do): read as the mass
/// of that weight under standard gravity ([`G_M_S2`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MassUnit {
    Kg,
    /// Metric tonne (1000 kg).
    T,
    Lb,
    Kips,
    /// US short ton.
    ShortTon,
    /// A weight of one kilonewton: 101.97 kg.
    #[serde(rename = "kN", alias = "kn")]
    KiloNewton,
    /// A weight of one decanewton: 1.0197 kg.
    #[serde(rename = "daN", alias = "dan")]
    DecaNewton,
}

impl MassUnit {
    pub fn to_kg(self) -> f64 {
        match self {
            MassUnit::Kg => 1.0,
            MassUnit::T => KG_PER_TONNE,
            MassUnit::Lb => KG_PER_LB,
            MassUnit::Kips => KG_PER_KIP,
            MassUnit::ShortTon => KG_PER_SHORT_TON,
            MassUnit::KiloNewton => 1000.0 / G_M_S2,
            MassUnit::DecaNewton => 10.0 / G_M_S2,
        }
    }
    /// Whether the unit is a weight's (a force's), not a mass's.
    pub fn is_force(self) -> bool {
        matches!(self, MassUnit::KiloNewton | MassUnit::DecaNewton)
    }
    pub fn name(self) -> &'static str {
        match self {
            MassUnit::Kg => "kg",
            MassUnit::T => "t",
            MassUnit::Lb => "lb",
            MassUnit::Kips => "kips",
            MassUnit::ShortTon => "short ton",
            MassUnit::KiloNewton => "kN",
            MassUnit::DecaNewton => "daN",
        }
    }
}

/// `swing` (rad) moved by whole turns into the range `[a, b]` (rad, from
/// the crane's heading, possibly across ±180°: [90°, 270°] behind it holds
/// -160° as 200°), if the range holds it.
pub fn swing_into_range(swing: f64, a: f64, b: f64) -> Option<f64> {
    let tau = std::f64::consts::TAU;
    let inside = swing + ((a - swing) / tau).ceil() * tau;
    (inside <= b + 1e-9).then_some(inside)
}

/// Wraps an angle to (-pi, pi].
pub fn wrap_pi(a: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let mut r = a.rem_euclid(two_pi);
    if r > std::f64::consts::PI {
        r -= two_pi;
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions() {
        assert!((MassUnit::Lb.to_kg() * 2_204.622_621_8 - 1000.0).abs() < 1e-6);
        assert!((LengthUnit::Ft.to_m() - 0.3048).abs() < 1e-12);
        assert!((wrap_pi(3.0 * std::f64::consts::PI) - std::f64::consts::PI).abs() < 1e-12);
        assert!((wrap_pi(-0.5) + 0.5).abs() < 1e-12);
        // A tonne weighs 9.80665 kN; a kilogram about a decanewton.
        assert!((MassUnit::KiloNewton.to_kg() * 9.806_65 - 1000.0).abs() < 1e-9);
        assert!((MassUnit::DecaNewton.to_kg() * 9.806_65 - 10.0).abs() < 1e-12);
        #[derive(serde::Deserialize)]
        struct Said {
            unit: MassUnit,
        }
        for (text, unit) in [("kN", MassUnit::KiloNewton), ("kn", MassUnit::KiloNewton), ("daN", MassUnit::DecaNewton)]
        {
            let said: Said = toml::from_str(&format!("unit = '{text}'")).unwrap();
            assert_eq!(said.unit, unit, "{text}");
        }
    }
}
