//! glTF 2.0 binary (.glb) through `gltf` / `gltf-json`.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::io::Write;

use gltf::json;
use json::validation::Checked::Valid;
use json::validation::USize64;

use super::{ExportError, FieldMesh};

/// The application-specific attribute name of a field: `_` + upper case (`_K`, `_H`, `_K1`).
pub fn attribute_name(field: &str) -> String {
    let mut s = String::from("_");
    s.extend(field.chars().map(|c| {
        if c.is_ascii_alphanumeric() {
            c.to_ascii_uppercase()
        } else {
            '_'
        }
    }));
    s
}

/// Appends little-endian bytes, padded to 4.
struct Bin {
    bytes: Vec<u8>,
}

impl Bin {
    fn view(
        &mut self,
        root: &mut json::Root,
        data: &[u8],
        target: Option<json::buffer::Target>,
    ) -> json::Index<json::buffer::View> {
        let offset = self.bytes.len();
        self.bytes.extend_from_slice(data);
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(data.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            target: target.map(Valid),
        })
    }
}

/// What an accessor describes: how many elements of which type, and optionally their bounds
/// and a name.
struct AccessorSpec {
    count: usize,
    component: json::accessor::ComponentType,
    type_: json::accessor::Type,
    normalized: bool,
    min_max: Option<([f32; 3], [f32; 3])>,
    name: Option<String>,
}

impl AccessorSpec {
    /// `count` elements of `type_` with components of `component`.
    fn new(
        count: usize,
        component: json::accessor::ComponentType,
        type_: json::accessor::Type,
    ) -> Self {
        AccessorSpec {
            count,
            component,
            type_,
            normalized: false,
            min_max: None,
            name: None,
        }
    }
}

/// The glTF document being built and its binary chunk.
struct GlbBuilder {
    root: json::Root,
    bin: Bin,
}

impl GlbBuilder {
    fn new() -> Self {
        let mut root = json::Root::default();
        root.asset.generator = Some("pssurf".into());
        GlbBuilder {
            root,
            bin: Bin { bytes: Vec::new() },
        }
    }

    /// Appends `data` as a buffer view and an accessor over it.
    fn accessor(
        &mut self,
        data: &[u8],
        target: json::buffer::Target,
        spec: AccessorSpec,
    ) -> json::Index<json::Accessor> {
        let view = self.bin.view(&mut self.root, data, Some(target));
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(spec.count),
            component_type: Valid(json::accessor::GenericComponentType(spec.component)),
            extensions: Default::default(),
            extras: Default::default(),
            type_: Valid(spec.type_),
            min: spec.min_max.map(|m| json::Value::from(m.0.to_vec())),
            max: spec.min_max.map(|m| json::Value::from(m.1.to_vec())),
            name: spec.name,
            normalized: spec.normalized,
            sparse: None,
        })
    }

    /// The vertex attributes: positions (with bounds), unit normals, colours, fields.
    fn attributes(
        &mut self,
        m: &FieldMesh<'_>,
    ) -> BTreeMap<json::validation::Checked<json::mesh::Semantic>, json::Index<json::Accessor>>
    {
        use json::accessor::{ComponentType as C, Type as T};
        use json::buffer::Target::ArrayBuffer;
        use json::mesh::Semantic;
        let n = m.mesh.positions.len();
        let mut attributes = BTreeMap::new();
        let positions = f32_bytes(
            m.mesh
                .positions
                .iter()
                .flat_map(|p| [p.x, p.y, p.z])
                .map(|x| x as f32),
        );
        let mut spec = AccessorSpec::new(n, C::F32, T::Vec3);
        spec.min_max = Some(position_bounds(m));
        let a = self.accessor(&positions, ArrayBuffer, spec);
        attributes.insert(Valid(Semantic::Positions), a);
        // NORMAL must be unit length: singular points (zero normal) get +z.
        let normals = f32_bytes(
            m.mesh
                .normals
                .iter()
                .flat_map(|p| {
                    if p.norm() > 0.5 {
                        [p.x, p.y, p.z]
                    } else {
                        [0.0, 0.0, 1.0]
                    }
                })
                .map(|x| x as f32),
        );
        let a = self.accessor(&normals, ArrayBuffer, AccessorSpec::new(n, C::F32, T::Vec3));
        attributes.insert(Valid(Semantic::Normals), a);
        if let Some(colors) = m.colors {
            let rgba: Vec<u8> = colors
                .iter()
                .flat_map(|c| [c[0], c[1], c[2], 255])
                .collect();
            let mut spec = AccessorSpec::new(n, C::U8, T::Vec4);
            spec.normalized = true;
            let a = self.accessor(&rgba, ArrayBuffer, spec);
            attributes.insert(Valid(Semantic::Colors(0)), a);
        }
        for (name, values) in m.fields {
            let data = f32_bytes(values.iter().map(|&x| x as f32));
            let mut spec = AccessorSpec::new(n, C::F32, T::Scalar);
            spec.name = Some(name.clone());
            let a = self.accessor(&data, ArrayBuffer, spec);
            let semantic = Semantic::Extras(attribute_name(name)[1..].to_string());
            attributes.insert(Valid(semantic), a);
        }
        attributes
    }

    /// One mesh of triangles in one node of the default scene.
    fn scene(&mut self, m: &FieldMesh<'_>) {
        use json::accessor::{ComponentType as C, Type as T};
        let attributes = self.attributes(m);
        let idx: Vec<u8> = m
            .mesh
            .triangles
            .iter()
            .flatten()
            .flat_map(|k| k.to_le_bytes())
            .collect();
        let indices = self.accessor(
            &idx,
            json::buffer::Target::ElementArrayBuffer,
            AccessorSpec::new(3 * m.mesh.triangles.len(), C::U32, T::Scalar),
        );
        let root = &mut self.root;
        root.push(json::Buffer {
            byte_length: USize64::from(self.bin.bytes.len()),
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            uri: None,
        });
        let primitive = json::mesh::Primitive {
            attributes,
            extensions: Default::default(),
            extras: Default::default(),
            indices: Some(indices),
            material: None,
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        };
        let mesh = root.push(json::Mesh {
            extensions: Default::default(),
            extras: Default::default(),
            name: Some("pssurf surface".into()),
            primitives: vec![primitive],
            weights: None,
        });
        let node = root.push(json::Node {
            mesh: Some(mesh),
            ..Default::default()
        });
        root.push(json::Scene {
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            nodes: vec![node],
        });
        root.scene = Some(json::Index::new(0));
    }

    /// The binary file: header, JSON chunk (padded with spaces), binary chunk.
    fn write(self, w: &mut dyn Write) -> Result<(), ExportError> {
        let mut text = json::serialize::to_string(&self.root)
            .map_err(|e| ExportError::Unsupported(e.to_string()))?
            .into_bytes();
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let length = 12 + 8 + text.len() + 8 + self.bin.bytes.len();
        let length = u32::try_from(length)
            .map_err(|_| ExportError::Unsupported("a .glb file holds at most 4 GiB".into()))?;
        let glb = gltf::binary::Glb {
            header: gltf::binary::Header {
                magic: *b"glTF",
                version: 2,
                length,
            },
            json: Cow::Owned(text),
            bin: Some(Cow::Owned(self.bin.bytes)),
        };
        glb.to_writer(w)
            .map_err(|e| ExportError::Unsupported(e.to_string()))
    }
}

/// The bounds of the positions as f32 (glTF requires them for POSITION).
fn position_bounds(m: &FieldMesh<'_>) -> ([f32; 3], [f32; 3]) {
    if m.mesh.positions.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &m.mesh.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k] as f32);
            hi[k] = hi[k].max(p[k] as f32);
        }
    }
    (lo, hi)
}

fn f32_bytes(values: impl Iterator<Item = f32>) -> Vec<u8> {
    values.flat_map(f32::to_le_bytes).collect()
}

/// Writes a .glb: one mesh with POSITION, NORMAL, COLOR_0 (normalised u8 RGBA) when colours
/// are given, one float attribute `_NAME` per field, and u32 indices.
pub fn write_glb(w: &mut dyn Write, m: &FieldMesh<'_>) -> Result<(), ExportError> {
    let mut glb = GlbBuilder::new();
    glb.scene(m);
    glb.write(w)
}
