//! The plate field as a VTK XML UnstructuredGrid (`.vtu`) that ParaView opens directly.
//!
//! Written with vtkio: inline base64 binary arrays of f64, so the values read back bit for
//! bit (a decimal ASCII file would round them). Geometry: the mesh nodes in 3-D with x along
//! the length, y across the width (the scene's z) and 0 out of plane; the elements as
//! VTK_QUAD cells in the JSON's counter-clockwise node order.
//!
//! Point data: `displacement` = (0, 0, w), so "Warp By Vector" bends the plate with no
//! calculator filter in between, and the scalars `w`, `w_x`, `w_z`. Cell data: the
//! element-centre moments `M_x`, `M_z`, `M_xz`, the surface bending stresses
//! `sigma_x`, `sigma_z`, `sigma_xz` (= 6M/h²), and `near_load` (1 on the elements touching
//! the load point, whose moments are a sampled point-load singularity and grow with
//! refinement; exclude them when reading off a maximum stress). Every value is for the load
//! `force_n` (N): linear elasticity, so the unit-load field times the force.
//!
//! What the file is: an XML comment before the root element carries the provenance (whose
//! opening is [`output::FILE_MARK`], so a later `--out` of the same name knows the file
//! as ours) and lines saying what the values are; the dataset's `FieldData` carries the load
//! and, where the load is an impact's P_max, the case's numbers and validity (ParaView shows
//! them in its Information panel, meshio reads them as `field_data`). No value that is not
//! finite is written: such a field is an error.

use crate::field::FieldFile;
use crate::provenance::Provenance;
use crate::Failure;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, IOBuffer, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

/// Names of the arrays, shared with the tests and reference/python/check_roundtrip.py.
pub const POINT_SCALARS: [&str; 3] = ["w", "w_x", "w_z"];
pub const MOMENTS: [&str; 3] = ["M_x", "M_z", "M_xz"];
pub const STRESSES: [&str; 3] = ["sigma_x", "sigma_z", "sigma_xz"];

/// What a `.vtu` says about itself beyond its arrays.
#[derive(Debug, Clone)]
pub struct Metadata {
    /// Where it came from; the first line of the comment.
    pub provenance: Provenance,
    /// Further comment lines: what the values are.
    pub lines: Vec<String>,
    /// Numbers for the dataset's `FieldData`, one single-value Float64 array each (the load
    /// `force_N` is always added).
    pub numbers: Vec<(String, f64)>,
}

/// The `.vtu` document for `field` under the load `force_n` (N), with `meta` in its comment
/// and field data. Refuses a load or a value that is not finite.
pub fn to_vtu(field: &FieldFile, force_n: f64, meta: &Metadata) -> Result<Vec<u8>, Failure> {
    if !(force_n.is_finite() && force_n > 0.0) {
        return Err(format!("the load of a .vtu must be a positive finite force, not {force_n} N").into());
    }
    let scale = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x * force_n).collect() };
    let points: Vec<f64> = field.points.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
    let connectivity: Vec<u64> = field.quads.iter().flatten().map(|&n| n as u64).collect();
    let offsets: Vec<u64> = (1..=field.quads.len() as u64).map(|i| 4 * i).collect();

    let pd = &field.point_data;
    let w = scale(&pd.w);
    let displacement: Vec<f64> = w.iter().flat_map(|&w| [0.0, 0.0, w]).collect();
    let mut point = vec![Attribute::vectors("displacement").with_data(displacement)];
    for (name, v) in POINT_SCALARS.iter().zip([&pd.w, &pd.w_x, &pd.w_z]) {
        point.push(Attribute::scalars(*name, 1).with_data(scale(v)));
    }

    let cd = &field.cell_data;
    let mut cell = Vec::new();
    for (name, v) in MOMENTS.iter().zip([&cd.m_x, &cd.m_z, &cd.m_xz]) {
        cell.push(Attribute::scalars(*name, 1).with_data(scale(v)));
    }
    for (name, v) in STRESSES.iter().zip(field.stresses()) {
        cell.push(Attribute::scalars(*name, 1).with_data(scale(&v)));
    }
    for a in point.iter().chain(&cell) {
        check_finite(a, force_n)?;
    }
    let near: Vec<u8> = field.near_load().into_iter().map(u8::from).collect();
    cell.push(Attribute::scalars("near_load", 1).with_data(IOBuffer::U8(near)));

    let vtk = Vtk {
        // 1.0: the version that allows the 64-bit block headers vtkio writes.
        version: Version::new((1, 0)),
        title: format!("{}, {}", field.scene, field.condition),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells: Cells {
                cell_verts: VertexNumbers::XML { connectivity, offsets },
                types: vec![CellType::Quad; field.quads.len()],
            },
            data: Attributes { point, cell },
        }),
    };
    let mut bytes = Vec::new();
    vtk.write_xml(&mut bytes)?;
    let mut numbers = vec![("force_N".to_string(), force_n)];
    numbers.extend(meta.numbers.iter().cloned());
    with_metadata(bytes, meta, &numbers)
}

/// An error if an array of `a` holds a value that is not finite (the load times a unit-load
/// value beyond f64's range).
fn check_finite(a: &Attribute, force_n: f64) -> Result<(), Failure> {
    if let Attribute::DataArray(d) = a {
        if let IOBuffer::F64(v) = &d.data {
            if let Some(bad) = v.iter().find(|x| !x.is_finite()) {
                return Err(format!(
                    "the field under {force_n} N has {} = {bad}: the load is too large for the numbers to be represented",
                    d.name
                )
                .into());
            }
        }
    }
    Ok(())
}

/// An XML comment's text: `--` may not occur in one, nor may it end in `-`.
fn comment_safe(text: &str) -> String {
    let mut s = text.replace('\n', " ");
    while s.contains("--") {
        s = s.replace("--", "- -");
    }
    if s.ends_with('-') {
        s.push(' ');
    }
    s
}

/// `xml` (vtkio's document, which starts at its root element) with an XML declaration, the
/// comment of `meta` before the root, and `numbers` as `FieldData` of the dataset element
/// (where VTK's own writers put it, before the first `Piece`).
fn with_metadata(xml: Vec<u8>, meta: &Metadata, numbers: &[(String, f64)]) -> Result<Vec<u8>, Failure> {
    if let Some((name, v)) = numbers.iter().find(|(_, v)| !v.is_finite()) {
        return Err(format!("field data {name} = {v} is not finite").into());
    }
    let xml = String::from_utf8(xml)?;
    let grid = "<UnstructuredGrid>";
    let at = xml.find(grid).ok_or("vtkio wrote no <UnstructuredGrid> element")? + grid.len();
    let mut out = String::with_capacity(xml.len() + 1024);
    out.push_str("<?xml version=\"1.0\"?>\n");
    let provenance = serde_json::to_string(&meta.provenance)?;
    for line in std::iter::once(format!("provenance {provenance}")).chain(meta.lines.iter().cloned()) {
        out.push_str(&format!("<!-- {} -->\n", comment_safe(&line)));
    }
    out.push_str(&xml[..at]);
    out.push_str("<FieldData>");
    for (name, v) in numbers {
        // `{:e}`: shortest round-trip digits, which VTK and numpy parse back exactly.
        out.push_str(&format!(
            "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfTuples=\"1\" format=\"ascii\">{v:e}</DataArray>"
        ));
    }
    out.push_str("</FieldData>");
    out.push_str(&xml[at..]);
    Ok(out.into_bytes())
}

/// Names of one frame's arrays in a time series, each with its SI unit: the point data
/// `displacement_m` = (0, 0, w) and `w_m`; the cell data, the element-centre moments and the
/// surface bending stresses σ = 6M/h², and `near_load` (1 on the elements touching the struck
/// point, whose moments sample the point-load singularity).
pub const FRAME_POINT: [&str; 2] = ["displacement_m", "w_m"];
/// See [`FRAME_POINT`].
pub const FRAME_MOMENTS: [&str; 3] = ["M_x_N_m_per_m", "M_z_N_m_per_m", "M_xz_N_m_per_m"];
/// See [`FRAME_POINT`].
pub const FRAME_STRESSES: [&str; 3] = ["sigma_x_Pa", "sigma_z_Pa", "sigma_xz_Pa"];

/// One frame of a time series as a `.vtu`: the mesh (nodes (x, z) in m, counter-clockwise
/// quads), the deflection `w` (m) at the nodes and the element-centre `moments` (N·m/m) of a
/// plate of `thickness` (m), struck at `load` (x, z); the arrays of [`FRAME_POINT`],
/// [`FRAME_MOMENTS`] and [`FRAME_STRESSES`], and `near_load`.
pub fn frame_vtu(
    title: &str,
    (nodes, quads): (&[[f64; 2]], &[[usize; 4]]),
    (w, moments): (&[f64], &[[f64; 3]]),
    thickness: f64,
    load: [f64; 2],
) -> Result<Vec<u8>, vtkio::Error> {
    let points: Vec<f64> = nodes.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
    let connectivity: Vec<u64> = quads.iter().flatten().map(|&n| n as u64).collect();
    let offsets: Vec<u64> = (1..=quads.len() as u64).map(|i| 4 * i).collect();
    let displacement: Vec<f64> = w.iter().flat_map(|&w| [0.0, 0.0, w]).collect();
    let six_over_h2 = 6.0 / (thickness * thickness);
    let mut cell = Vec::new();
    for (k, name) in FRAME_MOMENTS.iter().enumerate() {
        cell.push(Attribute::scalars(*name, 1).with_data(moments.iter().map(|m| m[k]).collect::<Vec<f64>>()));
    }
    for (k, name) in FRAME_STRESSES.iter().enumerate() {
        let sigma: Vec<f64> = moments.iter().map(|m| six_over_h2 * m[k]).collect();
        cell.push(Attribute::scalars(*name, 1).with_data(sigma));
    }
    let near: Vec<f64> = touching(nodes, quads, load).into_iter().map(|n| f64::from(u8::from(n))).collect();
    cell.push(Attribute::scalars("near_load", 1).with_data(near));
    let vtk = Vtk {
        version: Version::new((1, 0)),
        title: title.to_string(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells: Cells {
                cell_verts: VertexNumbers::XML { connectivity, offsets },
                types: vec![CellType::Quad; quads.len()],
            },
            data: Attributes {
                point: vec![
                    Attribute::vectors(FRAME_POINT[0]).with_data(displacement),
                    Attribute::scalars(FRAME_POINT[1], 1).with_data(w.to_vec()),
                ],
                cell,
            },
        }),
    };
    let mut bytes = Vec::new();
    vtk.write_xml(&mut bytes)?;
    Ok(bytes)
}

/// Per element: whether the closed rectangle contains the load point (to 1e-9 of the plate's
/// extent, so that a load typed in millimetres on a node touches every element sharing it).
fn touching(nodes: &[[f64; 2]], quads: &[[usize; 4]], [x, z]: [f64; 2]) -> Vec<bool> {
    let extent = nodes.iter().fold(0.0f64, |a, p| a.max(p[0].abs()).max(p[1].abs()));
    let tol = 1e-9 * extent;
    quads
        .iter()
        .map(|q| {
            let (lo, hi) = (nodes[q[0]], nodes[q[2]]);
            (lo[0] - tol..=hi[0] + tol).contains(&x) && (lo[1] - tol..=hi[1] + tol).contains(&z)
        })
        .collect()
}
