//! Binary little-endian PLY through `ply-rs-bw`.

use std::io::Write;

use ply_rs_bw::ply::{
    Addable, ElementDef, Encoding, Header, PropertyAccess, PropertyDef, PropertyType, ScalarType,
};
use ply_rs_bw::writer::Writer;

use super::{ExportError, FieldMesh};

/// The most scalar fields one vertex carries.
const MAX_FIELDS: usize = 16;

/// One vertex row: the property names are looked up in `names` (shared by all rows).
#[derive(Clone, Copy)]
struct VertexRow<'a> {
    names: &'a [String],
    values: [f32; 6 + MAX_FIELDS],
    rgb: [u8; 3],
}

impl PropertyAccess for VertexRow<'_> {
    fn new() -> Self {
        VertexRow {
            names: &[],
            values: [0.0; 6 + MAX_FIELDS],
            rgb: [0; 3],
        }
    }
    fn get_float(&self, name: &str) -> Option<f32> {
        let k = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            "nx" => 3,
            "ny" => 4,
            "nz" => 5,
            _ => 6 + self.names.iter().position(|n| n == name)?,
        };
        Some(self.values[k])
    }
    fn get_uchar(&self, name: &str) -> Option<u8> {
        match name {
            "red" => Some(self.rgb[0]),
            "green" => Some(self.rgb[1]),
            "blue" => Some(self.rgb[2]),
            _ => None,
        }
    }
}

#[derive(Clone, Copy)]
struct FaceRow {
    indices: [i32; 3],
}

impl PropertyAccess for FaceRow {
    fn new() -> Self {
        FaceRow { indices: [0; 3] }
    }
    fn get_list_int(&self, name: &str) -> Option<&[i32]> {
        (name == "vertex_indices").then_some(&self.indices[..])
    }
}

/// An edge of a polyline (`vertex1`, `vertex2`).
#[derive(Clone, Copy)]
struct EdgeRow {
    ends: [i32; 2],
}

impl PropertyAccess for EdgeRow {
    fn new() -> Self {
        EdgeRow { ends: [0; 2] }
    }
    fn get_int(&self, name: &str) -> Option<i32> {
        match name {
            "vertex1" => Some(self.ends[0]),
            "vertex2" => Some(self.ends[1]),
            _ => None,
        }
    }
}

fn scalar(name: &str, t: ScalarType) -> PropertyDef {
    PropertyDef::new(name.to_string(), PropertyType::Scalar(t))
}

/// Writes binary PLY: `x y z nx ny nz` as float, `red green blue` as uchar when colours are
/// given, then one float property per field; faces as `vertex_indices` (uchar count, int);
/// polylines as an `edge` element (`vertex1`, `vertex2`) over their own vertices after the
/// mesh's (zero normals, black, NaN fields).
pub fn write_ply(w: &mut dyn Write, m: &FieldMesh<'_>) -> Result<(), ExportError> {
    if m.fields.len() > MAX_FIELDS {
        return Err(ExportError::Unsupported(format!(
            "at most {MAX_FIELDS} fields"
        )));
    }
    let total = m.mesh.positions.len() + m.line_points();
    if total > i32::MAX as usize {
        return Err(ExportError::Unsupported(
            "PLY int indices hold at most 2³¹ − 1 vertices".into(),
        ));
    }
    let names: Vec<String> = m.fields.iter().map(|f| f.0.clone()).collect();
    let mut header = Header::new();
    header.encoding = Encoding::BinaryLittleEndian;
    header
        .comments
        .push("pssurf: points, normals and curvature of a Powell-Sabin surface".into());
    let mut vertex = ElementDef::new("vertex".to_string());
    for p in ["x", "y", "z", "nx", "ny", "nz"] {
        vertex.properties.add(scalar(p, ScalarType::Float));
    }
    if m.colors.is_some() {
        for p in ["red", "green", "blue"] {
            vertex.properties.add(scalar(p, ScalarType::UChar));
        }
    }
    for n in &names {
        vertex.properties.add(scalar(n, ScalarType::Float));
    }
    vertex.count = total;
    let mut face = ElementDef::new("face".to_string());
    face.properties.add(PropertyDef::new(
        "vertex_indices".to_string(),
        PropertyType::List(ScalarType::UChar, ScalarType::Int),
    ));
    face.count = m.mesh.triangles.len();
    let edges: Vec<EdgeRow> = m
        .line_indices()
        .into_iter()
        .flat_map(|r| {
            let (a, b) = (r.start, r.end);
            (a..b.saturating_sub(1)).map(|k| EdgeRow {
                ends: [k as i32, k as i32 + 1],
            })
        })
        .collect();
    let mut edge = ElementDef::new("edge".to_string());
    for p in ["vertex1", "vertex2"] {
        edge.properties.add(scalar(p, ScalarType::Int));
    }
    edge.count = edges.len();
    header.elements.add(vertex.clone());
    header.elements.add(face.clone());
    if !edges.is_empty() {
        header.elements.add(edge.clone());
    }

    let rows: Vec<VertexRow<'_>> = (0..m.mesh.positions.len())
        .map(|k| {
            let (p, n) = (m.mesh.positions[k], m.mesh.normals[k]);
            let mut values = [0.0f32; 6 + MAX_FIELDS];
            values[..6].copy_from_slice(&[p.x, p.y, p.z, n.x, n.y, n.z].map(|x| x as f32));
            for (f, (_, data)) in m.fields.iter().enumerate() {
                values[6 + f] = data[k] as f32;
            }
            VertexRow {
                names: &names,
                values,
                rgb: m.colors.map_or([0; 3], |c| c[k]),
            }
        })
        .chain(m.lines.iter().flatten().map(|p| {
            let mut values = [f32::NAN; 6 + MAX_FIELDS];
            values[..6].copy_from_slice(&[p.x as f32, p.y as f32, p.z as f32, 0.0, 0.0, 0.0]);
            VertexRow {
                names: &names,
                values,
                rgb: [0; 3],
            }
        }))
        .collect();
    let faces: Vec<FaceRow> = m
        .mesh
        .triangles
        .iter()
        .map(|t| FaceRow {
            indices: t.map(|k| k as i32),
        })
        .collect();
    let mut out = std::io::BufWriter::new(w);
    Writer::<VertexRow<'_>>::new().write_header(&mut out, &header)?;
    Writer::<VertexRow<'_>>::new().write_payload_of_element(&mut out, &rows, &vertex, &header)?;
    Writer::<FaceRow>::new().write_payload_of_element(&mut out, &faces, &face, &header)?;
    if !edges.is_empty() {
        Writer::<EdgeRow>::new().write_payload_of_element(&mut out, &edges, &edge, &header)?;
    }
    out.flush()?;
    Ok(())
}
