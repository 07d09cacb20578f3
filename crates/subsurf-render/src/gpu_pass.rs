//! The render pass: surface, then lines, into a multisampled sRGB target, resolved and read
//! back row by row.

use crate::camera::{add, normalize, scale, Camera};
use crate::device::Gpu;
use crate::image::RgbaImage;
use crate::prepare::{SurfaceVertices, Vertex};
use crate::{RenderError, RenderOptions};
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct Uniforms {
    view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    key: [f32; 4],
    line_color: [f32; 4],
    viewport: [f32; 4],
    shading: [f32; 4],
}

/// sRGB byte to linear intensity.
fn linear(c: u8) -> f32 {
    let x = c as f32 / 255.0;
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

fn uniforms(cam: &Camera, o: &RenderOptions) -> Uniforms {
    let e = cam.eye;
    // Key light from the upper left, slightly in front: direction in camera axes.
    let key_dir = normalize(add(
        add(scale(cam.right, -0.45), scale(cam.up, 0.75)),
        scale(normalize(crate::camera::sub(cam.eye, cam.target)), 0.5),
    ));
    let key_intensity = if o.key_light { 0.5 } else { 0.0 };
    let headlight = if o.key_light { 0.5 } else { 0.85 };
    Uniforms {
        view_proj: cam.view_proj(),
        eye: [e[0], e[1], e[2], 1.0],
        key: [key_dir[0], key_dir[1], key_dir[2], key_intensity],
        line_color: [
            linear(o.line_color[0]),
            linear(o.line_color[1]),
            linear(o.line_color[2]),
            1.0,
        ],
        viewport: [
            o.width as f32,
            o.height as f32,
            o.line_width,
            2e-3 * cam.radius,
        ],
        shading: [0.1, headlight, 0.15, 32.0],
    }
}

fn check_size(gpu: &Gpu, what: &str, bytes: u64) -> Result<(), RenderError> {
    let max = gpu.device.limits().max_buffer_size;
    if bytes > max {
        return Err(RenderError::TooLarge(format!(
            "{what}: {bytes} bytes > device buffer limit {max}"
        )));
    }
    Ok(())
}

/// Draws the surface and lines and reads the image back.
pub(crate) fn draw(
    gpu: &Gpu,
    surf: &SurfaceVertices,
    lines: &[[[f32; 3]; 2]],
    cam: &Camera,
    o: &RenderOptions,
) -> Result<RgbaImage, RenderError> {
    let dev = &gpu.device;
    let max_dim = dev.limits().max_texture_dimension_2d;
    if o.width > max_dim || o.height > max_dim {
        return Err(RenderError::TooLarge(format!(
            "image {}x{} > device texture limit {max_dim}",
            o.width, o.height
        )));
    }
    check_size(
        gpu,
        "vertex buffer",
        (surf.vertices.len() * std::mem::size_of::<Vertex>()) as u64,
    )?;
    check_size(gpu, "index buffer", (surf.indices.len() * 4) as u64)?;
    let scope = dev.push_error_scope(wgpu::ErrorFilter::Validation);

    let samples = if o.samples > 1
        && gpu
            .adapter
            .get_texture_format_features(COLOR_FORMAT)
            .flags
            .sample_count_supported(o.samples)
    {
        o.samples
    } else {
        1
    };

    let shader = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("subsurf-render shader"),
        source: wgpu::ShaderSource::Wgsl(include_str!("shader.wgsl").into()),
    });
    let u = uniforms(cam, o);
    let ubuf = dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("uniforms"),
        contents: bytemuck::bytes_of(&u),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let bgl = dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("uniforms"),
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
    });
    let bind = dev.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("uniforms"),
        layout: &bgl,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: ubuf.as_entire_binding(),
        }],
    });
    let layout = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("subsurf-render"),
        bind_group_layouts: &[Some(&bgl)],
        immediate_size: 0,
    });
    let target = [Some(wgpu::ColorTargetState {
        format: COLOR_FORMAT,
        blend: None,
        write_mask: wgpu::ColorWrites::ALL,
    })];
    let multisample = wgpu::MultisampleState {
        count: samples,
        mask: !0,
        alpha_to_coverage_enabled: false,
    };
    let surface_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Unorm8x4];
    let surface_pipeline = dev.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("surface"),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &shader,
            entry_point: Some("vs_surface"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &surface_attrs,
            })],
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face: wgpu::FrontFace::Ccw,
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample,
        fragment: Some(wgpu::FragmentState {
            module: &shader,
            entry_point: Some("fs_surface"),
            compilation_options: Default::default(),
            targets: &target,
        }),
        multiview_mask: None,
        cache: None,
    });
    let line_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
    let line_pipeline = dev.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("lines"),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &shader,
            entry_point: Some("vs_line"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 24,
                step_mode: wgpu::VertexStepMode::Instance,
                attributes: &line_attrs,
            })],
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(false),
            depth_compare: Some(wgpu::CompareFunction::LessEqual),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample,
        fragment: Some(wgpu::FragmentState {
            module: &shader,
            entry_point: Some("fs_line"),
            compilation_options: Default::default(),
            targets: &target,
        }),
        multiview_mask: None,
        cache: None,
    });

    let size = wgpu::Extent3d {
        width: o.width,
        height: o.height,
        depth_or_array_layers: 1,
    };
    let texture = |label, format, samples, usage| {
        dev.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size,
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    let resolved = texture(
        "resolved",
        COLOR_FORMAT,
        1,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let msaa = (samples > 1).then(|| {
        texture(
            "msaa colour",
            COLOR_FORMAT,
            samples,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        )
    });
    let depth = texture(
        "depth",
        DEPTH_FORMAT,
        samples,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    );
    let resolved_view = resolved.create_view(&Default::default());
    let msaa_view = msaa.as_ref().map(|t| t.create_view(&Default::default()));
    let depth_view = depth.create_view(&Default::default());

    let bg = o.background;
    let clear = wgpu::Color {
        r: linear(bg[0]) as f64,
        g: linear(bg[1]) as f64,
        b: linear(bg[2]) as f64,
        a: bg[3] as f64 / 255.0,
    };
    let vbuf = (!surf.indices.is_empty()).then(|| {
        (
            dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("vertices"),
                contents: bytemuck::cast_slice(&surf.vertices),
                usage: wgpu::BufferUsages::VERTEX,
            }),
            dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("indices"),
                contents: bytemuck::cast_slice(&surf.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
        )
    });
    let lbuf = (!lines.is_empty()).then(|| {
        dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("lines"),
            contents: bytemuck::cast_slice(lines),
            usage: wgpu::BufferUsages::VERTEX,
        })
    });

    let row_bytes = 4 * o.width;
    let padded =
        row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let readback = dev.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: padded as u64 * o.height as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });

    let mut enc = dev.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("render"),
    });
    {
        let (view, resolve_target) = match &msaa_view {
            Some(m) => (m, Some(&resolved_view)),
            None => (&resolved_view, None),
        };
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("render"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(clear),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &bind, &[]);
        if let Some((vb, ib)) = &vbuf {
            pass.set_pipeline(&surface_pipeline);
            pass.set_vertex_buffer(0, vb.slice(..));
            pass.set_index_buffer(ib.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..surf.indices.len() as u32, 0, 0..1);
        }
        if let Some(lb) = &lbuf {
            pass.set_pipeline(&line_pipeline);
            pass.set_vertex_buffer(0, lb.slice(..));
            pass.draw(0..6, 0..lines.len() as u32);
        }
    }
    enc.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: &resolved,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(o.height),
            },
        },
        size,
    );
    gpu.queue.submit([enc.finish()]);
    if let Some(err) = pollster::block_on(scope.pop()) {
        return Err(RenderError::Device(err.to_string()));
    }

    let slice = readback.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    dev.poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| RenderError::Device(e.to_string()))?;
    rx.recv()
        .map_err(|e| RenderError::Device(e.to_string()))?
        .map_err(|e| RenderError::Device(e.to_string()))?;
    let mut data = Vec::with_capacity((row_bytes * o.height) as usize);
    {
        let view = slice
            .get_mapped_range()
            .map_err(|e| RenderError::Device(e.to_string()))?;
        for row in view.chunks(padded as usize) {
            data.extend_from_slice(&row[..row_bytes as usize]);
        }
    }
    readback.unmap();
    Ok(RgbaImage {
        width: o.width,
        height: o.height,
        data,
    })
}
