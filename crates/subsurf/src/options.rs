//! Subdivision options, with OpenSubdiv's defaults (as used by its regression shapes).

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
    /// Face-varying interpolation rule.
    pub fvar_interpolation: FVarLinearInterpolation,
    /// OpenSubdiv's `facevaryingpropagatecorners` tag.
    pub fvar_propagate_corners: bool,
}
