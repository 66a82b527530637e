//! Saving and reloading a bake (feature `serde`): the polygon set is written as its
//! polygons (face, corners, plane normal and offset) and rebuilt on load.

use std::sync::Arc;

use face_sort::glam::DVec3;
use face_sort::{Plane, PolygonSet};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::axis::Axis;
use crate::cells::{AngleRange, Bake, BakeCell, Breakpoint, Method};

#[derive(Serialize, Deserialize)]
struct PolygonData {
    face: u32,
    corners: Vec<[f64; 3]>,
    normal: [f64; 3],
    offset: f64,
}

#[derive(Serialize, Deserialize)]
struct BakeData {
    axis: Axis,
    sorter: String,
    method: Method,
    domain: AngleRange,
    polygons: Vec<PolygonData>,
    cells: Vec<BakeCell>,
    breakpoints: Vec<Breakpoint>,
    events: usize,
    bake_ms: f64,
}

impl Serialize for Bake {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let set = &self.polygons;
        let polygons = (0..set.len())
            .map(|i| PolygonData {
                face: set.face(i),
                corners: set.corners(i).iter().map(|c| c.to_array()).collect(),
                normal: set.plane(i).normal().to_array(),
                offset: set.plane(i).offset(),
            })
            .collect();
        BakeData {
            axis: self.axis,
            sorter: self.sorter.clone(),
            method: self.method,
            domain: self.domain,
            polygons,
            cells: self.cells.clone(),
            breakpoints: self.breakpoints.clone(),
            events: self.events,
            bake_ms: self.bake_ms,
        }
        .serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Bake {
    /// Planes are rebuilt from normal and offset (`Plane::try_from_point_normal`, which
    /// normalises again: equal to the saved plane up to the last bit). A polygon with a zero
    /// normal, or a cell naming a polygon that is not there, is an error.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let data = BakeData::deserialize(deserializer)?;
        let mut set = PolygonSet::new();
        let mut corners = Vec::new();
        for (i, p) in data.polygons.iter().enumerate() {
            let normal = DVec3::from_array(p.normal);
            let plane =
                Plane::try_from_point_normal(normal * p.offset, normal).ok_or_else(|| {
                    serde::de::Error::custom(format!("polygon {i}: the plane normal is zero"))
                })?;
            corners.clear();
            corners.extend(p.corners.iter().map(|&c| DVec3::from_array(c)));
            set.push(&corners, p.face, plane);
        }
        let n = set.len();
        for (k, cell) in data.cells.iter().enumerate() {
            if let Some(bad) = cell.order.iter().find(|&&p| p as usize >= n) {
                return Err(serde::de::Error::custom(format!(
                    "cell {k}: polygon {bad} of {n}"
                )));
            }
        }
        Ok(Bake {
            axis: data.axis,
            sorter: data.sorter,
            method: data.method,
            domain: data.domain,
            polygons: Arc::new(set),
            cells: data.cells,
            breakpoints: data.breakpoints,
            events: data.events,
            bake_ms: data.bake_ms,
        })
    }
}

impl Bake {
    /// The bake in a compact binary encoding (postcard: serde's data model, integers as
    /// varints, `f64` as 8 bytes), for saving and shipping; [`Bake::from_binary`] reads it back.
    ///
    /// # Errors
    /// The encoder's message, should serialisation fail.
    pub fn to_binary(&self) -> Result<Vec<u8>, String> {
        postcard::to_allocvec(self).map_err(|e| e.to_string())
    }

    /// A bake from [`Bake::to_binary`]'s bytes, checked as a deserialised bake is (planes with
    /// a normal, cells naming existing polygons).
    ///
    /// # Errors
    /// What is wrong with the bytes.
    pub fn from_binary(bytes: &[u8]) -> Result<Bake, String> {
        postcard::from_bytes(bytes).map_err(|e| e.to_string())
    }
}
