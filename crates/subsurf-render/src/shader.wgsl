// Smooth-shaded surface with a two-sided headlight and a key light, and screen-space thick
// lines for the control-cage overlay.

struct Uniforms {
    view_proj: mat4x4<f32>,
    // xyz: eye position.
    eye: vec4<f32>,
    // xyz: unit direction towards the key light; w: its intensity.
    key: vec4<f32>,
    // rgb: line colour (linear).
    line_color: vec4<f32>,
    // x, y: viewport size in pixels; z: line width in pixels; w: world offset towards the eye.
    viewport: vec4<f32>,
    // x: ambient, y: headlight, z: specular, w: shininess.
    shading: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

struct SurfaceIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
};

struct SurfaceOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec3<f32>,
};

@vertex
fn vs_surface(v: SurfaceIn) -> SurfaceOut {
    var o: SurfaceOut;
    o.clip = u.view_proj * vec4<f32>(v.position, 1.0);
    o.world = v.position;
    o.normal = v.normal;
    o.color = pow(v.color.rgb, vec3<f32>(2.2));
    return o;
}

@fragment
fn fs_surface(i: SurfaceOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var n = i.normal;
    let len = length(n);
    let to_eye = normalize(u.eye.xyz - i.world);
    if (len > 1e-20) {
        n = n / len;
    } else {
        n = to_eye;
    }
    // Two-sided: back faces are lit as if their normal pointed the other way.
    if (!front) {
        n = -n;
    }
    let head = abs(dot(n, to_eye));
    let l = u.key.xyz;
    let key = max(dot(n, l), 0.0) * u.key.w;
    let h = normalize(l + to_eye);
    let spec = u.shading.z * (u.key.w * pow(max(dot(n, h), 0.0), u.shading.w)
        + pow(head, u.shading.w * 2.0) * 0.5);
    let base = i.color;
    let c = base * (u.shading.x + u.shading.y * head + key) + vec3<f32>(spec);
    return vec4<f32>(c, 1.0);
}

struct LineOut {
    @builtin(position) clip: vec4<f32>,
};

@vertex
fn vs_line(
    @builtin(vertex_index) vi: u32,
    @location(0) a: vec3<f32>,
    @location(1) b: vec3<f32>,
) -> LineOut {
    // Pull both ends slightly towards the eye so that lines on the surface win the depth test.
    let pa = a + normalize(u.eye.xyz - a) * u.viewport.w;
    let pb = b + normalize(u.eye.xyz - b) * u.viewport.w;
    let ca = u.view_proj * vec4<f32>(pa, 1.0);
    let cb = u.view_proj * vec4<f32>(pb, 1.0);
    let half_px = 0.5 * u.viewport.xy;
    let sa = ca.xy / ca.w * half_px;
    let sb = cb.xy / cb.w * half_px;
    var dir = sb - sa;
    if (length(dir) < 1e-6) {
        dir = vec2<f32>(1.0, 0.0);
    }
    dir = normalize(dir);
    let side = vec2<f32>(-dir.y, dir.x);
    // Two triangles: (0,-1) (1,-1) (1,1) / (0,-1) (1,1) (0,1) as (end, side).
    var ends = array<f32, 6>(0.0, 1.0, 1.0, 0.0, 1.0, 0.0);
    var sides = array<f32, 6>(-1.0, -1.0, 1.0, -1.0, 1.0, 1.0);
    let t = ends[vi % 6u];
    let s = sides[vi % 6u];
    let c = mix(ca, cb, t);
    let w = 0.5 * u.viewport.z;
    // Extend by half a width along the segment so that joints close.
    let offset_px = side * s * w + dir * (2.0 * t - 1.0) * w;
    var o: LineOut;
    o.clip = vec4<f32>(c.xy + offset_px / half_px * c.w, c.z, c.w);
    return o;
}

@fragment
fn fs_line() -> @location(0) vec4<f32> {
    return vec4<f32>(u.line_color.rgb, 1.0);
}
