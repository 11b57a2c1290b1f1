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

use crate::report::field::FieldFile;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, IOBuffer, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

/// Names of the arrays, shared with the tests and reference/python/check_roundtrip.py.
pub const POINT_SCALARS: [&str; 3] = ["w", "w_x", "w_z"];
pub const MOMENTS: [&str; 3] = ["M_x", "M_z", "M_xz"];
pub const STRESSES: [&str; 3] = ["sigma_x", "sigma_z", "sigma_xz"];

/// The `.vtu` document for `field` under the load `force_n` (N).
pub fn to_vtu(field: &FieldFile, force_n: f64) -> Result<Vec<u8>, vtkio::Error> {
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
    Ok(bytes)
}

/// A deflection field alone as a `.vtu`: the mesh (nodes (x, z) in m, counter-clockwise
/// quads) with the point data `displacement` = (0, 0, w) and `w`, m. One frame of a time
/// series.
pub fn deflection_vtu(
    title: &str,
    nodes: &[[f64; 2]],
    quads: &[[usize; 4]],
    w: &[f64],
) -> Result<Vec<u8>, vtkio::Error> {
    let points: Vec<f64> = nodes.iter().flat_map(|p| [p[0], p[1], 0.0]).collect();
    let connectivity: Vec<u64> = quads.iter().flatten().map(|&n| n as u64).collect();
    let offsets: Vec<u64> = (1..=quads.len() as u64).map(|i| 4 * i).collect();
    let displacement: Vec<f64> = w.iter().flat_map(|&w| [0.0, 0.0, w]).collect();
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
                    Attribute::vectors("displacement").with_data(displacement),
                    Attribute::scalars("w", 1).with_data(w.to_vec()),
                ],
                cell: vec![],
            },
        }),
    };
    let mut bytes = Vec::new();
    vtk.write_xml(&mut bytes)?;
    Ok(bytes)
}
