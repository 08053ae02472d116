// Draws the 3D view's offscreen colour target into egui's render pass.

@group(0) @binding(0) var offscreen: texture_2d<f32>;
@group(0) @binding(1) var offscreen_sampler: sampler;

struct FullOut {
    @builtin(position) pos: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_full(@builtin(vertex_index) i: u32) -> FullOut {
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    var out: FullOut;
    out.pos = vec4<f32>(2.0 * x - 1.0, 1.0 - 2.0 * y, 0.0, 1.0);
    out.uv = vec2<f32>(x, y);
    return out;
}

@fragment
fn fs_full_gamma(in: FullOut) -> @location(0) vec4<f32> {
    return textureSample(offscreen, offscreen_sampler, in.uv);
}

// For an sRGB target the hardware encodes, so decode our gamma-space colours first.
@fragment
fn fs_full_linear(in: FullOut) -> @location(0) vec4<f32> {
    let c = textureSample(offscreen, offscreen_sampler, in.uv);
    let lo = c.rgb / 12.92;
    let hi = pow((c.rgb + 0.055) / 1.055, vec3<f32>(2.4));
    return vec4<f32>(select(hi, lo, c.rgb <= vec3<f32>(0.04045)), c.a);
}
