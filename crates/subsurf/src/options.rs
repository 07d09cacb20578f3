//! Subdivision options, with OpenSubdiv's defaults (as used by its regression shapes).
//!
//! Every option enum has one name per value ([`OptionValue`], `Display`, `FromStr`): the
//! spelling of the command line, the Python package and `docs/vocabulary.md`. File formats
//! keep their own tokens in one table each, next to the format (`io::obj_tags`, `io::usd`).

/// The subdivision scheme. All three refine uniformly; limit patches are Catmull-Clark only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Scheme {
    /// Catmull-Clark (Catmull & Clark 1978), OpenSubdiv's `SCHEME_CATMARK`.
    #[default]
    Catmark,
    /// Bilinear subdivision: every new point is an average of its parents.
    Bilinear,
    /// Loop subdivision (triangles only): uniform refinement, stencils and limit stencils.
    Loop,
}

/// How boundary vertices are interpolated (OpenSubdiv `Sdc::Options::VtxBoundaryInterpolation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum BoundaryInterpolation {
    /// No boundary interpolation: faces at unsharpened boundary vertices become holes.
    None,
    /// Boundary edges are infinitely sharp.
    #[default]
    EdgeOnly,
    /// Boundary edges are infinitely sharp and boundary vertices of valence 2 are corners.
    EdgeAndCorner,
}

/// How semi-sharp creases decay from level to level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum CreaseMethod {
    /// Sharpness decreases by one each level (RenderMan).
    #[default]
    Uniform,
    /// Chaikin's rule: a child edge's sharpness averages its neighbours' (DeRose et al. 1998).
    Chaikin,
}

/// Rule used for triangles in the Catmull-Clark scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum TriangleSubdivision {
    /// The plain Catmull-Clark rule.
    #[default]
    Catmark,
    /// The modified face-point weights of Stam & Loop for smoother triangles.
    Smooth,
}

/// Face-varying (UV) interpolation (OpenSubdiv `Sdc::Options::FVarLinearInterpolation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum FVarLinearInterpolation {
    /// Smooth everywhere, boundaries included.
    None,
    /// Sharpen corners only.
    CornersOnly,
    /// Sharpen corners and some junctions (variant 1).
    CornersPlus1,
    /// Sharpen corners and some junctions (variant 2).
    CornersPlus2,
    /// Sharpen every face-varying boundary.
    Boundaries,
    /// Linear everywhere (bilinear UVs). OpenSubdiv's default.
    #[default]
    All,
}

/// All options that shape the surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Options {
    /// Subdivision scheme.
    pub scheme: Scheme,
    /// Boundary interpolation rule.
    pub boundary: BoundaryInterpolation,
    /// Crease decay rule.
    pub crease_method: CreaseMethod,
    /// Triangle rule (Catmull-Clark only).
    pub triangle_subdivision: TriangleSubdivision,
    /// Face-varying (UV) interpolation rule (OpenSubdiv's `fvarLinearInterpolation`; the
    /// `uv_interpolation` of the command line and Python, see `docs/vocabulary.md`).
    pub uv_interpolation: FVarLinearInterpolation,
    /// OpenSubdiv's `facevaryingpropagatecorners` tag.
    pub fvar_propagate_corners: bool,
}

/// An option whose values have one name each: the spelling of the command line, the Python
/// package and `docs/vocabulary.md`. [`std::fmt::Display`] writes it and [`std::str::FromStr`]
/// reads it back (an unknown name is a [`ParseOptionError`] that lists the accepted ones).
/// File formats with their own tokens (OBJ tag integers, USD tokens) keep one table each, next
/// to the format, as a function of the value; their readers invert it with [`Self::find`].
pub trait OptionValue: Copy + Eq + std::fmt::Debug + Send + Sync + 'static {
    /// What the option is called in messages (`"scheme"`, `"boundary"`, ...).
    const OPTION: &'static str;
    /// Every value, in the order the names are listed.
    const ALL: &'static [Self];
    /// The value's name.
    fn name(self) -> &'static str;
    /// Every name, in the order of [`Self::ALL`].
    fn names() -> impl Iterator<Item = &'static str> {
        Self::ALL.iter().map(|v| v.name())
    }
    /// The value whose name is `name`.
    fn from_name(name: &str) -> Result<Self, ParseOptionError> {
        Self::find(|v| v.name() == name).ok_or_else(|| ParseOptionError::new::<Self>(name))
    }
    /// The first value for which `pred` holds: a format's token table inverted
    /// (`Scheme::find(|s| usd_token(s) == t)`).
    fn find(pred: impl Fn(Self) -> bool) -> Option<Self> {
        Self::ALL.iter().copied().find(|&v| pred(v))
    }
}

/// A name that is not one of an option's values.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseOptionError {
    /// The option ([`OptionValue::OPTION`]).
    pub option: &'static str,
    /// The name given.
    pub given: String,
    /// The accepted names.
    pub accepted: Vec<&'static str>,
}

impl ParseOptionError {
    /// The error for `given`, an unknown name of `T`.
    pub fn new<T: OptionValue>(given: &str) -> Self {
        ParseOptionError {
            option: T::OPTION,
            given: given.to_string(),
            accepted: T::names().collect(),
        }
    }
}

impl std::fmt::Display for ParseOptionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} {:?}: use {}",
            self.option,
            self.given,
            self.accepted.join(", ")
        )
    }
}

impl std::error::Error for ParseOptionError {}

/// Implements [`OptionValue`], [`std::fmt::Display`] and [`std::str::FromStr`] for a
/// field-less enum from its one list of names:
/// `option_value!(Scheme, "scheme", { Catmark => "catmark", Bilinear => "bilinear" });`.
#[macro_export]
macro_rules! option_value {
    ($ty:ty, $option:literal, { $($variant:ident => $name:literal),+ $(,)? }) => {
        impl $crate::OptionValue for $ty {
            const OPTION: &'static str = $option;
            const ALL: &'static [Self] = &[$(<$ty>::$variant),+];
            fn name(self) -> &'static str {
                match self {
                    $(<$ty>::$variant => $name),+
                }
            }
        }
        impl ::std::fmt::Display for $ty {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str($crate::OptionValue::name(*self))
            }
        }
        impl ::std::str::FromStr for $ty {
            type Err = $crate::ParseOptionError;
            fn from_str(s: &str) -> ::std::result::Result<Self, Self::Err> {
                <$ty as $crate::OptionValue>::from_name(s)
            }
        }
    };
}

option_value!(Scheme, "scheme", {
    Catmark => "catmark",
    Bilinear => "bilinear",
    Loop => "loop",
});

option_value!(BoundaryInterpolation, "boundary", {
    None => "none",
    EdgeOnly => "edge-only",
    EdgeAndCorner => "edge-and-corner",
});

option_value!(CreaseMethod, "crease_method", {
    Uniform => "uniform",
    Chaikin => "chaikin",
});

option_value!(TriangleSubdivision, "triangle_subdivision", {
    Catmark => "catmark",
    Smooth => "smooth",
});

option_value!(FVarLinearInterpolation, "uv_interpolation", {
    None => "none",
    CornersOnly => "corners-only",
    CornersPlus1 => "corners-plus1",
    CornersPlus2 => "corners-plus2",
    Boundaries => "boundaries",
    All => "linear",
});

#[cfg(test)]
mod tests {
    use super::*;

    /// `FromStr(Display(x)) == x` for every value, names distinct, unknown names refused
    /// with the accepted ones listed.
    fn round_trip<
        T: OptionValue + std::fmt::Display + std::str::FromStr<Err = ParseOptionError>,
    >() {
        let mut seen = std::collections::HashSet::new();
        for &v in T::ALL {
            let s = v.to_string();
            assert_eq!(s, v.name());
            assert_eq!(s.parse::<T>(), Ok(v), "{s}");
            assert!(seen.insert(s.clone()), "{} {s} named twice", T::OPTION);
        }
        let e = "no-such-value".parse::<T>().unwrap_err();
        assert_eq!(e.option, T::OPTION);
        let msg = e.to_string();
        assert!(msg.contains("no-such-value"), "{msg}");
        for name in T::names() {
            assert!(msg.contains(name), "{msg}");
        }
    }

    #[test]
    fn every_option_round_trips() {
        round_trip::<Scheme>();
        round_trip::<BoundaryInterpolation>();
        round_trip::<CreaseMethod>();
        round_trip::<TriangleSubdivision>();
        round_trip::<FVarLinearInterpolation>();
        round_trip::<crate::surface::Colors>();
        round_trip::<crate::surface::MethodName>();
        round_trip::<crate::surface::BackendName>();
    }
}
