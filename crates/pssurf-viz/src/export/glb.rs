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

#[allow(clippy::too_many_arguments)]
fn accessor(
    root: &mut json::Root,
    view: json::Index<json::buffer::View>,
    count: usize,
    component: json::accessor::ComponentType,
    type_: json::accessor::Type,
    normalized: bool,
    min_max: Option<([f32; 3], [f32; 3])>,
    name: Option<String>,
) -> json::Index<json::Accessor> {
    root.push(json::Accessor {
        buffer_view: Some(view),
        byte_offset: None,
        count: USize64::from(count),
        component_type: Valid(json::accessor::GenericComponentType(component)),
        extensions: Default::default(),
        extras: Default::default(),
        type_: Valid(type_),
        min: min_max.map(|m| json::Value::from(m.0.to_vec())),
        max: min_max.map(|m| json::Value::from(m.1.to_vec())),
        name,
        normalized,
        sparse: None,
    })
}

fn f32_bytes(values: impl Iterator<Item = f32>) -> Vec<u8> {
    values.flat_map(f32::to_le_bytes).collect()
}

/// Writes a .glb: one mesh with POSITION, NORMAL, COLOR_0 (normalised u8 RGBA) when colours
/// are given, one float attribute `_NAME` per field, and u32 indices.
pub fn write_glb(w: &mut dyn Write, m: &FieldMesh<'_>) -> Result<(), ExportError> {
    let n = m.mesh.positions.len();
    let mut root = json::Root::default();
    root.asset.generator = Some("pssurf".into());
    let mut bin = Bin { bytes: Vec::new() };
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &m.mesh.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k] as f32);
            hi[k] = hi[k].max(p[k] as f32);
        }
    }
    if n == 0 {
        (lo, hi) = ([0.0; 3], [0.0; 3]);
    }
    use json::accessor::{ComponentType as C, Type as T};
    use json::buffer::Target;
    let mut attributes = BTreeMap::new();
    let v = bin.view(
        &mut root,
        &f32_bytes(
            m.mesh
                .positions
                .iter()
                .flat_map(|p| [p.x, p.y, p.z])
                .map(|x| x as f32),
        ),
        Some(Target::ArrayBuffer),
    );
    attributes.insert(
        Valid(json::mesh::Semantic::Positions),
        accessor(
            &mut root,
            v,
            n,
            C::F32,
            T::Vec3,
            false,
            Some((lo, hi)),
            None,
        ),
    );
    let v = bin.view(
        &mut root,
        &f32_bytes(
            m.mesh
                .normals
                .iter()
                .flat_map(|p| {
                    // NORMAL must be unit length: singular points (zero normal) get +z.
                    if p.norm() > 0.5 {
                        [p.x, p.y, p.z]
                    } else {
                        [0.0, 0.0, 1.0]
                    }
                })
                .map(|x| x as f32),
        ),
        Some(Target::ArrayBuffer),
    );
    attributes.insert(
        Valid(json::mesh::Semantic::Normals),
        accessor(&mut root, v, n, C::F32, T::Vec3, false, None, None),
    );
    if let Some(colors) = m.colors {
        let rgba: Vec<u8> = colors
            .iter()
            .flat_map(|c| [c[0], c[1], c[2], 255])
            .collect();
        let v = bin.view(&mut root, &rgba, Some(Target::ArrayBuffer));
        attributes.insert(
            Valid(json::mesh::Semantic::Colors(0)),
            accessor(&mut root, v, n, C::U8, T::Vec4, true, None, None),
        );
    }
    for (name, values) in m.fields {
        let v = bin.view(
            &mut root,
            &f32_bytes(values.iter().map(|&x| x as f32)),
            Some(Target::ArrayBuffer),
        );
        let a = accessor(
            &mut root,
            v,
            n,
            C::F32,
            T::Scalar,
            false,
            None,
            Some(name.clone()),
        );
        attributes.insert(
            Valid(json::mesh::Semantic::Extras(
                attribute_name(name)[1..].to_string(),
            )),
            a,
        );
    }
    let idx: Vec<u8> = m
        .mesh
        .triangles
        .iter()
        .flatten()
        .flat_map(|k| k.to_le_bytes())
        .collect();
    let v = bin.view(&mut root, &idx, Some(Target::ElementArrayBuffer));
    let indices = accessor(
        &mut root,
        v,
        3 * m.mesh.triangles.len(),
        C::U32,
        T::Scalar,
        false,
        None,
        None,
    );
    root.push(json::Buffer {
        byte_length: USize64::from(bin.bytes.len()),
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
    let mut text = json::serialize::to_string(&root)
        .map_err(|e| ExportError::Unsupported(e.to_string()))?
        .into_bytes();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let length = 12 + 8 + text.len() + 8 + bin.bytes.len();
    let length = u32::try_from(length)
        .map_err(|_| ExportError::Unsupported("a .glb file holds at most 4 GiB".into()))?;
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length,
        },
        json: Cow::Owned(text),
        bin: Some(Cow::Owned(bin.bytes)),
    };
    glb.to_writer(w)
        .map_err(|e| ExportError::Unsupported(e.to_string()))?;
    Ok(())
}
