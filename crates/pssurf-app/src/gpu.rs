//! The GPU side of the 3D view: surfaces and overlay lines are drawn into an offscreen
//! colour + depth target (so the view has its own depth buffer whatever egui's pass has),
//! which an `egui_wgpu` paint callback then composites into the UI. The same renderer draws
//! headless pictures.

use std::ops::Range;
use std::sync::Arc;

use eframe::egui_wgpu::{self, wgpu};
use wgpu::util::DeviceExt;

use crate::display::{GpuVertex, LineVertex};

/// The offscreen colour format (gamma-space colours, as egui uses).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// The offscreen depth format.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The view's background colour.
pub const BACKGROUND: [f64; 3] = [0.965, 0.968, 0.975];

/// The shader uniforms (see `view.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Uniforms {
    /// Projection × view.
    pub view_proj: [[f32; 4]; 4],
    /// Eye position; w = 1 for perspective.
    pub eye: [f32; 4],
    /// Direction to the eye.
    pub to_eye: [f32; 4],
    /// Direction to the light.
    pub light: [f32; 4],
    /// Zebra axis.
    pub axis: [f32; 4],
    /// Mode, band width (rad), flat, lit.
    pub params: [f32; 4],
}

/// The geometry of one frame, shared with the paint callback; `generation` changes whenever
/// the content does, so that it is uploaded only then, and `history` says which ranges the
/// last local updates rewrote, so that a renderer holding an earlier generation uploads only
/// those.
#[derive(Clone, Debug, Default)]
pub struct FrameGeometry {
    /// Identifies the content.
    pub generation: u64,
    /// Surface vertices of all visible objects.
    pub vertices: Vec<GpuVertex>,
    /// Their triangles.
    pub indices: Vec<u32>,
    /// Overlay segments.
    pub lines: Vec<LineVertex>,
    /// The latest local updates, oldest first, each leading from one generation to the next
    /// (empty after a full rebuild).
    pub history: Vec<LocalUpdate>,
}

/// Extra lines drawn over the scene (the probe's), uploaded when `generation` changes.
#[derive(Clone, Debug, Default)]
pub struct LineSet {
    /// Identifies the content.
    pub generation: u64,
    /// Line-list vertices.
    pub lines: Vec<LineVertex>,
}

/// Ranges rewritten in place between two generations (the sizes did not change).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LocalUpdate {
    /// The generation before.
    pub from: u64,
    /// The generation after.
    pub to: u64,
    /// Rewritten ranges of `vertices`.
    pub vertices: Vec<Range<usize>>,
    /// Rewritten ranges of `lines`.
    pub lines: Vec<Range<usize>>,
}

/// How many local updates a [`FrameGeometry`] remembers.
pub const HISTORY: usize = 16;

impl FrameGeometry {
    /// Records that the given ranges were rewritten in place: a new generation.
    pub fn record(&mut self, vertices: Vec<Range<usize>>, lines: Vec<Range<usize>>) {
        let from = self.generation;
        self.generation = crate::scene::fresh_revision();
        self.history.push(LocalUpdate {
            from,
            to: self.generation,
            vertices,
            lines,
        });
        if self.history.len() > HISTORY {
            self.history.remove(0);
        }
    }

    /// The local updates that lead from generation `from` to the current one, if they are
    /// all remembered.
    pub fn updates_since(&self, from: u64) -> Option<&[LocalUpdate]> {
        let start = self.history.iter().position(|u| u.from == from)?;
        Some(&self.history[start..])
    }
}

struct Buffers {
    generation: u64,
    vertices: wgpu::Buffer,
    vertex_count: usize,
    indices: wgpu::Buffer,
    index_count: u32,
    lines: wgpu::Buffer,
    line_count: u32,
}

impl Buffers {
    fn new(device: &wgpu::Device, g: &FrameGeometry) -> Self {
        let make = |label, contents: &[u8], usage| {
            // Empty buffers are not allowed: keep at least one element's room.
            let padded;
            let contents = if contents.is_empty() {
                padded = vec![0u8; 64];
                &padded[..]
            } else {
                contents
            };
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let rewritable = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST;
        Buffers {
            generation: g.generation,
            vertices: make(
                "pssurf vertices",
                bytemuck::cast_slice(&g.vertices),
                rewritable,
            ),
            vertex_count: g.vertices.len(),
            indices: make(
                "pssurf indices",
                bytemuck::cast_slice(&g.indices),
                wgpu::BufferUsages::INDEX,
            ),
            index_count: g.indices.len() as u32,
            lines: make("pssurf lines", bytemuck::cast_slice(&g.lines), rewritable),
            line_count: g.lines.len() as u32,
        }
    }

    /// Whether `g` has the sizes of these buffers (so ranges can be rewritten in place).
    fn fits(&self, g: &FrameGeometry) -> bool {
        self.vertex_count == g.vertices.len()
            && self.index_count as usize == g.indices.len()
            && self.line_count as usize == g.lines.len()
    }
}

/// Writes the given element ranges of `data` into `buffer` at the same offsets.
fn write_ranges<T: bytemuck::Pod>(
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    data: &[T],
    ranges: &[Range<usize>],
) {
    let size = std::mem::size_of::<T>();
    for r in ranges {
        let bytes: &[u8] = bytemuck::cast_slice(&data[r.clone()]);
        // Copies must be multiples of 4 bytes; both element types are.
        queue.write_buffer(buffer, (r.start * size) as u64, bytes);
    }
}

struct Target {
    size: [u32; 2],
    color: wgpu::Texture,
    color_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
}

/// Draws frames into its offscreen target.
pub struct ViewRenderer {
    surface: wgpu::RenderPipeline,
    lines: wgpu::RenderPipeline,
    uniforms: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    buffers: Option<Buffers>,
    extra: Option<(u64, wgpu::Buffer, u32)>,
    target: Option<Target>,
    /// Bumped whenever the target texture is recreated.
    pub target_generation: u64,
    /// How many uploads were full and how many rewrote only ranges.
    pub uploads: UploadCounts,
}

/// Counts of the two kinds of geometry upload.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UploadCounts {
    /// New buffers with everything.
    pub full: usize,
    /// Only the ranges of local updates.
    pub partial: usize,
}

impl ViewRenderer {
    /// Compiles the pipelines.
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("pssurf view"),
            source: wgpu::ShaderSource::Wgsl(include_str!("view.wgsl").into()),
        });
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pssurf view uniforms"),
            size: std::mem::size_of::<Uniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = uniform_layout(device);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("pssurf view uniforms"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniforms.as_entire_binding(),
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("pssurf view"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let surface = surface_pipeline(device, &module, &pipeline_layout);
        let lines = line_pipeline(device, &module, &pipeline_layout);
        ViewRenderer {
            surface,
            lines,
            uniforms,
            bind_group,
            buffers: None,
            extra: None,
            target: None,
            target_generation: 0,
            uploads: UploadCounts::default(),
        }
    }

    /// Uploads the geometry if it changed since the last upload: only the rewritten ranges
    /// when the buffers hold a generation that the geometry's history leads from, everything
    /// otherwise.
    pub fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, g: &FrameGeometry) {
        let Some(b) = &mut self.buffers else {
            self.buffers = Some(Buffers::new(device, g));
            self.uploads.full += 1;
            return;
        };
        if b.generation == g.generation {
            return;
        }
        match g.updates_since(b.generation) {
            Some(updates) if b.fits(g) => {
                for u in updates {
                    write_ranges(queue, &b.vertices, &g.vertices, &u.vertices);
                    write_ranges(queue, &b.lines, &g.lines, &u.lines);
                }
                b.generation = g.generation;
                self.uploads.partial += 1;
            }
            _ => {
                *b = Buffers::new(device, g);
                self.uploads.full += 1;
            }
        }
    }

    /// Uploads the extra lines if they changed.
    pub fn upload_lines(&mut self, device: &wgpu::Device, set: &LineSet) {
        if self
            .extra
            .as_ref()
            .is_some_and(|(g, ..)| *g == set.generation)
        {
            return;
        }
        self.extra = (!set.lines.is_empty()).then(|| {
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("pssurf extra lines"),
                contents: bytemuck::cast_slice(&set.lines),
                usage: wgpu::BufferUsages::VERTEX,
            });
            (set.generation, buffer, set.lines.len() as u32)
        });
    }

    fn ensure_target(&mut self, device: &wgpu::Device, size: [u32; 2]) {
        let size = [size[0].max(1), size[1].max(1)];
        if self.target.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        let texture = |format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some("pssurf view target"),
                size: wgpu::Extent3d {
                    width: size[0],
                    height: size[1],
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = texture(
            COLOR_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let depth = texture(DEPTH_FORMAT, wgpu::TextureUsages::RENDER_ATTACHMENT);
        self.target = Some(Target {
            size,
            color_view: color.create_view(&Default::default()),
            color,
            depth_view: depth.create_view(&Default::default()),
        });
        self.target_generation += 1;
    }

    /// Draws the uploaded geometry into the offscreen target of `size` pixels.
    pub fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        size: [u32; 2],
        uniforms: &Uniforms,
    ) {
        self.ensure_target(device, size);
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(uniforms));
        let target = self.target.as_ref().expect("just made");
        let [r, g, b] = BACKGROUND;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("pssurf view"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target.color_view,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: 1.0 }),
                    store: wgpu::StoreOp::Store,
                },
                depth_slice: None,
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &target.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        let Some(b) = &self.buffers else {
            return;
        };
        pass.set_bind_group(0, &self.bind_group, &[]);
        if b.index_count > 0 {
            pass.set_pipeline(&self.surface);
            pass.set_vertex_buffer(0, b.vertices.slice(..));
            pass.set_index_buffer(b.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..b.index_count, 0, 0..1);
        }
        pass.set_pipeline(&self.lines);
        if b.line_count > 0 {
            pass.set_vertex_buffer(0, b.lines.slice(..));
            pass.draw(0..b.line_count, 0..1);
        }
        if let Some((_, extra, count)) = &self.extra {
            pass.set_vertex_buffer(0, extra.slice(..));
            pass.draw(0..*count, 0..1);
        }
    }

    /// The offscreen colour texture (after a render).
    pub fn color_texture(&self) -> Option<&wgpu::Texture> {
        self.target.as_ref().map(|t| &t.color)
    }

    fn color_view(&self) -> Option<&wgpu::TextureView> {
        self.target.as_ref().map(|t| &t.color_view)
    }
}

/// The layout of the view's bind group: the uniform buffer, seen by both shader stages.
fn uniform_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("pssurf view uniforms"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    })
}

/// What sets a view pipeline apart: shader entry points, primitive topology, vertex layout.
struct PipelineSpec<'a> {
    /// The vertex shader's entry point (also the pipeline's label).
    vertex: &'a str,
    /// The fragment shader's entry point.
    fragment: &'a str,
    /// Triangles or lines.
    topology: wgpu::PrimitiveTopology,
    /// The vertex attributes.
    attributes: &'a [wgpu::VertexAttribute],
    /// The size of one vertex in bytes.
    stride: usize,
}

/// The pipeline that draws surfaces: triangles of [`GpuVertex`] (position, normal, colour).
fn surface_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    layout: &wgpu::PipelineLayout,
) -> wgpu::RenderPipeline {
    let attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Unorm8x4];
    let spec = PipelineSpec {
        vertex: "vs_surface",
        fragment: "fs_surface",
        topology: wgpu::PrimitiveTopology::TriangleList,
        attributes: &attributes,
        stride: std::mem::size_of::<GpuVertex>(),
    };
    view_pipeline(device, module, layout, &spec)
}

/// The pipeline that draws overlay lines: line segments of [`LineVertex`] (position, colour).
fn line_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    layout: &wgpu::PipelineLayout,
) -> wgpu::RenderPipeline {
    let attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Unorm8x4];
    let spec = PipelineSpec {
        vertex: "vs_line",
        fragment: "fs_line",
        topology: wgpu::PrimitiveTopology::LineList,
        attributes: &attributes,
        stride: std::mem::size_of::<LineVertex>(),
    };
    view_pipeline(device, module, layout, &spec)
}

/// A view-shader pipeline into the offscreen target: no culling, depth test, no blending.
fn view_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    layout: &wgpu::PipelineLayout,
    spec: &PipelineSpec,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.vertex),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(spec.vertex),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: spec.stride as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: spec.attributes,
            })],
            compilation_options: Default::default(),
        },
        primitive: wgpu::PrimitiveState {
            topology: spec.topology,
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::LessEqual),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(spec.fragment),
            targets: &[Some(wgpu::ColorTargetState {
                format: COLOR_FORMAT,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
            compilation_options: Default::default(),
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Draws the offscreen target into egui's pass.
pub struct Compositor {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    bind_group: Option<(u64, wgpu::BindGroup)>,
}

impl Compositor {
    /// A compositor for egui's target format.
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("pssurf composite"),
            source: wgpu::ShaderSource::Wgsl(include_str!("composite.wgsl").into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("pssurf composite"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        multisampled: false,
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("pssurf composite"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("pssurf composite"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_full"),
                buffers: &[],
                compilation_options: Default::default(),
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(if target_format.is_srgb() {
                    "fs_full_linear"
                } else {
                    "fs_full_gamma"
                }),
                targets: &[Some(wgpu::ColorTargetState {
                    format: target_format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
                compilation_options: Default::default(),
            }),
            multiview_mask: None,
            cache: None,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor::default());
        Compositor {
            pipeline,
            layout,
            sampler,
            bind_group: None,
        }
    }

    fn update(&mut self, device: &wgpu::Device, renderer: &ViewRenderer) {
        let generation = renderer.target_generation;
        if self
            .bind_group
            .as_ref()
            .is_some_and(|(g, _)| *g == generation)
        {
            return;
        }
        let Some(view) = renderer.color_view() else {
            return;
        };
        let bg = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("pssurf composite"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.sampler),
                },
            ],
        });
        self.bind_group = Some((generation, bg));
    }
}

/// What the paint callback needs, kept in egui_wgpu's callback resources.
pub struct ViewResources {
    /// The offscreen renderer.
    pub renderer: ViewRenderer,
    /// The composite into egui.
    pub compositor: Compositor,
}

impl ViewResources {
    /// Registers the resources with an egui_wgpu render state (call once at start-up).
    pub fn install(state: &egui_wgpu::RenderState) {
        let resources = ViewResources {
            renderer: ViewRenderer::new(&state.device),
            compositor: Compositor::new(&state.device, state.target_format),
        };
        state.renderer.write().callback_resources.insert(resources);
    }
}

/// The per-frame paint callback of the 3D view.
pub struct ViewCallback {
    /// The geometry to draw.
    pub geometry: Arc<FrameGeometry>,
    /// The probe's lines.
    pub extra: Arc<LineSet>,
    /// Camera, light and mode.
    pub uniforms: Uniforms,
    /// The view's size in pixels.
    pub size: [u32; 2],
}

impl egui_wgpu::CallbackTrait for ViewCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if let Some(r) = resources.get_mut::<ViewResources>() {
            r.renderer.upload(device, queue, &self.geometry);
            r.renderer.upload_lines(device, &self.extra);
            r.renderer
                .render(device, queue, encoder, self.size, &self.uniforms);
            r.compositor.update(device, &r.renderer);
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: eframe::egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        let Some(r) = resources.get::<ViewResources>() else {
            return;
        };
        let Some((_, bg)) = &r.compositor.bind_group else {
            return;
        };
        pass.set_pipeline(&r.compositor.pipeline);
        pass.set_bind_group(0, bg, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// Draws a picture of `size` pixels offscreen with a renderer of its own (so the view on
/// screen is not disturbed) and reads it back.
pub fn render_picture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    geometry: &FrameGeometry,
    extra: &LineSet,
    uniforms: &Uniforms,
    size: [u32; 2],
) -> Result<image::RgbaImage, String> {
    let mut r = ViewRenderer::new(device);
    r.upload(device, queue, geometry);
    r.upload_lines(device, extra);
    let mut encoder = device.create_command_encoder(&Default::default());
    r.render(device, queue, &mut encoder, size, uniforms);
    queue.submit([encoder.finish()]);
    read_texture(device, queue, r.color_texture().expect("just rendered"))
}

/// Reads a texture (RGBA8) back into an image.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<image::RgbaImage, String> {
    let (w, h) = (texture.width(), texture.height());
    let row = 4 * w as usize;
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as usize;
    let padded = row.div_ceil(align) * align;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("pssurf readback"),
        size: (padded * h as usize) as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded as u32),
                rows_per_image: None,
            },
        },
        wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
    );
    let index = queue.submit([encoder.finish()]);
    let (tx, rx) = std::sync::mpsc::channel();
    buffer
        .slice(..)
        .map_async(wgpu::MapMode::Read, move |r| drop(tx.send(r)));
    device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(index),
            timeout: Some(std::time::Duration::from_secs(30)),
        })
        .map_err(|e| format!("waiting for the GPU: {e}"))?;
    rx.recv()
        .map_err(|e| e.to_string())?
        .map_err(|e| e.to_string())?;
    let data = buffer
        .slice(..)
        .get_mapped_range()
        .map_err(|e| e.to_string())?;
    let pixels: Vec<u8> = data
        .chunks_exact(padded)
        .flat_map(|r| r[..row].iter().copied())
        .collect();
    image::RgbaImage::from_raw(w, h, pixels).ok_or_else(|| "readback size mismatch".to_string())
}
