// The 3D view: surfaces (shaded, curvature colours, zebra stripes) and overlay lines into an
// offscreen colour + depth target, and the composite that draws that target into egui.

struct Uniforms {
    view_proj: mat4x4<f32>,
    // xyz: the eye; w: 1 for perspective, 0 for orthographic.
    eye: vec4<f32>,
    // The direction towards the eye (orthographic).
    to_eye: vec4<f32>,
    // The direction towards the light.
    light: vec4<f32>,
    // The zebra axis (in the screen plane).
    axis: vec4<f32>,
    // x: mode (0 shaded, 1 colours, 2 zebra, 3 hidden-line wireframe); y: band width
    // (radians); z: flat; w: lit colours.
    params: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

// The view's background (gpu.rs BACKGROUND).
const BACKGROUND: vec3<f32> = vec3<f32>(0.965, 0.968, 0.975);

struct SurfaceOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec4<f32>,
};

@vertex
fn vs_surface(@location(0) pos: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) color: vec4<f32>) -> SurfaceOut {
    var out: SurfaceOut;
    out.clip = u.view_proj * vec4<f32>(pos, 1.0);
    out.world = pos;
    out.normal = normal;
    out.color = color;
    return out;
}

@fragment
fn fs_surface(in: SurfaceOut) -> @location(0) vec4<f32> {
    if (u.params.x > 2.5) {
        // Wireframe: the surface only hides the edges behind it.
        return vec4<f32>(BACKGROUND, 1.0);
    }
    let face = cross(dpdx(in.world), dpdy(in.world));
    var n = in.normal;
    if (u.params.z > 0.5 || dot(n, n) < 1e-12) {
        n = face;
    }
    n = normalize(n);
    var v = u.to_eye.xyz;
    if (u.eye.w > 0.5) {
        v = normalize(u.eye.xyz - in.world);
    }
    var back = false;
    if (dot(n, v) < 0.0) {
        n = -n;
        back = true;
    }
    let mode = u.params.x;
    if (mode > 1.5) {
        // Zebra: bands of latitude of the reflected view ray about the axis.
        let r = reflect(-v, n);
        let lat = asin(clamp(dot(r, u.axis.xyz), -1.0, 1.0));
        let band = abs(floor(lat / u.params.y) % 2.0);
        // Two real colours, neither of them the background's: ink and a warm yellow.
        let dark = vec3<f32>(0.07, 0.08, 0.12);
        let light = vec3<f32>(1.0, 0.86, 0.35);
        return vec4<f32>(select(dark, light, band < 0.5), 1.0);
    }
    var base = in.color.rgb;
    // Shaded: the material's colour, its glossiness in alpha; back faces warm.
    var gloss = in.color.a;
    if (mode < 0.5) {
        if (back) {
            base = vec3<f32>(0.86, 0.62, 0.45);
            gloss = 0.15;
        }
    } else if (u.params.w < 0.5) {
        return vec4<f32>(base, 1.0);
    }
    let l = u.light.xyz;
    let diffuse = max(dot(n, l), 0.0);
    let h = normalize(l + v);
    let specular = (0.05 + 0.55 * gloss) * pow(max(dot(n, h), 0.0), 8.0 + 120.0 * gloss);
    return vec4<f32>(base * (0.28 + 0.72 * diffuse) + vec3<f32>(specular), 1.0);
}

struct LineOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
};

@vertex
fn vs_line(@location(0) pos: vec3<f32>, @location(1) color: vec4<f32>) -> LineOut {
    var out: LineOut;
    var c = u.view_proj * vec4<f32>(pos, 1.0);
    // Pull lines slightly towards the eye so that lines on the surface win the depth test.
    c.z = c.z - 5e-4 * c.w;
    out.clip = c;
    out.color = color;
    return out;
}

@fragment
fn fs_line(in: LineOut) -> @location(0) vec4<f32> {
    // Unused room in a line slot (see display.rs) is transparent.
    if (in.color.a < 0.5) {
        discard;
    }
    return in.color;
}
