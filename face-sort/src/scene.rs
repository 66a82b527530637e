//! Scenes of many objects: meshes shared by instances, ordered coarse to fine.
//!
//! A [`SceneSorter`] holds each mesh once, with its BSP built once, and places it by any
//! number of [`Instance`]s (an affine world transform each: rotations, non-uniform and
//! nested scales, mirrors). A frame:
//!
//! 1. **Objects** are culled by their world box against the image.
//! 2. **Coarse order.** The instances' world boxes are split by axis-aligned planes that
//!    separate them (every box entirely on one side), as in the flight simulator's AA-BSP:
//!    across such a plane, the side away from the viewer is drawn first, and no face of one
//!    side can cover a face of the other that is farther from the viewer. The split nearest
//!    the middle is taken, on any axis; the tree is rebuilt only when an instance moves (it
//!    is O(n log n) in the instances).
//! 3. **Fine order.** A leaf with one object is drawn by its mesh's own BSP, the viewer
//!    mapped into the mesh's frame ([`CullTest::transformed`]): plane sides are preserved by
//!    affine maps, so nothing is rebuilt per instance or per frame. A leaf whose boxes
//!    interlock (no plane separates them) is a **cluster**: the members' faces in world
//!    space, ordered by Newell while the cluster is new (a member that moves makes a new
//!    cluster every frame, and Newell needs no tree), and by one BSP over them once the
//!    cluster has been drawn unchanged for a few frames.
//!
//! Instances are drawn layer by layer ([`Layer`]: background, main, overlay), each layer
//! ordered as above. An instance may carry coarser meshes for when it is small in the image
//! ([`Instance::with_lod`]): each frame picks one by the size of its box on screen; its faces
//! keep one numbering (the largest level's count, unused numbers never drawn). A billboard instance ([`Instance::as_billboard`]) is turned to face
//! the image plane whenever the view turns, and is then ordered like any other (a stack of
//! translucent billboards makes a volumetric cloud, exact against the objects inside it).
//!
//! The output is an ordinary [`DrawList`] in the scene's centred world coordinates (the
//! view must be fitted to [`SceneSorter::bounds`]), with faces numbered as in
//! [`SceneSorter::flattened`]: instance by instance, each instance's faces in its mesh's
//! order. A mirrored instance (negative determinant) keeps each face's own front, as glTF
//! asks of mirrored nodes, and is drawn with its corners reversed so that world winding
//! and front agree.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{DAffine3, DVec3};

use crate::{
    Bounds, Bsp, CullTest, DrawList, FaceSorter, Geometry, MeshError, Plane, PolygonMesh,
    PolygonSet, View, Viewer,
};

/// One placement of a mesh: `world = transform · local`, in a layer.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Instance {
    /// Index of the mesh in the scene's meshes.
    pub mesh: usize,
    /// Local to world.
    pub transform: DAffine3,
    /// The rendering queue it is drawn in.
    pub layer: Layer,
    /// A billboard: `transform`'s linear part applies in the camera's frame (local `+z`
    /// toward the viewer, local `+y` up the screen), so the mesh faces the image plane
    /// whatever the view; its translation places it in the world.
    pub billboard: bool,
    /// Coarser meshes for when the instance is small in the image: `(mesh, below_px)` uses
    /// `mesh` while the instance's box spans fewer than `below_px` pixels (its projected
    /// diagonal); among several, the smallest threshold that applies wins.
    pub lods: [Option<(usize, f64)>; MAX_LODS],
    /// A material override for all of the instance's faces: an id the caller's sinks resolve
    /// to a brush (e.g. raster-sink's `Style`), found back by
    /// [`SceneSorter::material_of_face`]; `None` keeps the mesh's own materials.
    pub material: Option<u32>,
}

/// Coarser meshes an instance may carry ([`Instance::with_lod`]).
pub const MAX_LODS: usize = 4;

impl Instance {
    /// Mesh `mesh` placed by `transform`, in the main layer.
    #[must_use]
    pub fn new(mesh: usize, transform: DAffine3) -> Self {
        Instance {
            mesh,
            transform,
            layer: Layer::Main,
            billboard: false,
            lods: [None; MAX_LODS],
            material: None,
        }
    }

    /// The same instance with a material override (see [`material`](Self::material)).
    #[must_use]
    pub fn with_material(mut self, material: u32) -> Self {
        self.material = Some(material);
        self
    }

    /// The same instance with one more level of detail: `mesh` while the instance spans
    /// fewer than `below_px` pixels in the image. Ignored beyond [`MAX_LODS`] levels.
    #[must_use]
    pub fn with_lod(mut self, mesh: usize, below_px: f64) -> Self {
        if let Some(slot) = self.lods.iter_mut().find(|l| l.is_none()) {
            *slot = Some((mesh, below_px));
        }
        self
    }

    /// The same instance as a billboard (see [`billboard`](Self::billboard)).
    #[must_use]
    pub fn as_billboard(mut self) -> Self {
        self.billboard = true;
        self
    }

    /// The same instance in `layer`.
    #[must_use]
    pub fn with_layer(mut self, layer: Layer) -> Self {
        self.layer = layer;
        self
    }
}

/// Rendering queues, drawn in this order: everything in one queue is ordered exactly
/// among itself, and nothing of a later queue is hidden by an earlier one.
///
/// There is no separate queue for translucent faces: a z-buffer renderer needs one (drawn
/// last, sorted by object distance) because its depth test cannot order them, but an exact
/// painter's order composites translucent and opaque faces correctly in one queue, across
/// interlocking objects too (raster-sink's `composite_truth` checks it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Layer {
    /// Drawn first, behind everything (a sky, a backdrop).
    Background,
    /// The scene, opaque and translucent faces together.
    #[default]
    Main,
    /// Drawn last, on top of everything (gizmos, labels, a HUD).
    Overlay,
}

impl Layer {
    /// The layers in drawing order.
    pub const ALL: [Layer; 3] = [Layer::Background, Layer::Main, Layer::Overlay];
}

/// Why a [`SceneSorter`] could not be built.
#[derive(Debug, thiserror::Error, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum SceneError {
    /// An instance names a mesh that does not exist.
    #[error("instance {instance} names mesh {mesh}, but the scene has {meshes} meshes")]
    NoSuchMesh {
        /// The instance.
        instance: usize,
        /// The mesh it names.
        mesh: usize,
        /// Number of meshes.
        meshes: usize,
    },
    /// An instance's transform is not invertible or not finite.
    #[error("instance {instance}: its transform is singular or not finite")]
    SingularTransform {
        /// The instance.
        instance: usize,
    },
    /// A mesh (or the scene) has no area or is out of range.
    #[error("mesh {mesh}: {source}")]
    Mesh {
        /// The mesh (the scene's count for the whole scene).
        mesh: usize,
        /// Why.
        source: MeshError,
    },
    /// The scene has no instance.
    #[error("the scene has no instance")]
    Empty,
}

/// What the last frame did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneStats {
    /// Instances drawn (not culled by their box).
    pub objects_drawn: usize,
    /// Instances whose box lies outside the image.
    pub objects_culled: usize,
    /// Leaves of the coarse order with interlocking instances.
    pub clusters: usize,
    /// Clusters made (their members' faces gathered) since the sorter was made.
    pub cluster_builds: usize,
    /// Cluster BSPs built (for clusters that stayed still) since the sorter was made.
    pub cluster_trees: usize,
    /// Coarse trees built since the sorter was made.
    pub tree_builds: usize,
}

struct SceneMesh {
    mesh: PolygonMesh,
    centre: DVec3,
    bounds: Bounds,
    sorter: MeshSorter,
}

/// How a mesh's instances are ordered: one sorter per mesh, the viewer mapped into each
/// instance's frame.
enum MeshSorter {
    Bsp(Bsp),
    Presorted(Box<crate::Presorted>),
}

impl MeshSorter {
    fn sort_culled(&mut self, cull: &CullTest, out: &mut DrawList) {
        match self {
            MeshSorter::Bsp(bsp) => bsp.sort_culled(cull, out),
            MeshSorter::Presorted(presorted) => presorted.sort_culled(cull, out),
        }
    }
}

/// The coarse order: axis-aligned planes between instance boxes.
enum Node {
    Split {
        axis: usize,
        at: f64,
        below: usize,
        above: usize,
    },
    Leaf(Vec<usize>),
}

/// Interlocking instances ordered together: their faces in world space, in the scene's frame
/// ([`Geometry::new_in_frame`]).
struct Cluster {
    geometry: Geometry,
    /// Newell while the cluster is new (no tree to pay for while its members move), a BSP
    /// once it has been drawn unchanged for [`SETTLED_FRAMES`] frames.
    sorter: ClusterSorter,
    /// Frames drawn since it was made.
    frames: u32,
    /// Cluster face → scene face.
    faces: Vec<u32>,
}

enum ClusterSorter {
    Newell(Box<crate::Newell>),
    Bsp(Bsp),
}

/// Frames a cluster is drawn unchanged (its members still) before its BSP is built.
const SETTLED_FRAMES: u32 = 8;

/// Orders the faces of a scene of instances (module docs).
pub struct SceneSorter {
    meshes: Vec<SceneMesh>,
    /// The instances, billboards with their transform for the last view.
    instances: Vec<Instance>,
    /// Billboards: instance and the placement its caller gave (camera-frame linear part).
    billboards: Vec<(usize, DAffine3)>,
    /// The view rotation the billboards face.
    billboard_rotation: Option<glam::DMat3>,
    face_offsets: Vec<u32>,
    /// Per instance: the faces it numbers (its largest level of detail's face count).
    slots: Vec<u32>,
    /// Per instance: the mesh drawn now (its own, or a level of detail).
    active: Vec<usize>,
    /// Per instance: the inverse of its transform (world to local), kept from placement.
    inverses: Vec<DAffine3>,
    boxes: Vec<Bounds>,
    bounds: Bounds,
    /// One coarse tree per layer, in [`Layer::ALL`] order.
    trees: [Vec<Node>; 3],
    tree_dirty: bool,
    clusters: HashMap<Vec<usize>, Cluster>,
    stats: SceneStats,
    // Per-frame scratch.
    leaves: Vec<usize>,
    stack: Vec<usize>,
    members: Vec<usize>,
    local: DrawList,
    corners: Vec<DVec3>,
    empty: Arc<PolygonSet>,
}

impl SceneSorter {
    /// A scene of `instances` of `meshes`. Builds each mesh's BSP once. The scene's
    /// [`bounds`](Self::bounds) (its frame of reference: fit views to it) are those of the
    /// instances' vertices now; they stay when instances move, unless set again.
    pub fn new(meshes: Vec<PolygonMesh>, instances: Vec<Instance>) -> Result<Self, SceneError> {
        let scene_meshes = meshes
            .into_iter()
            .enumerate()
            .map(|(k, mesh)| {
                let geometry =
                    Geometry::new(&mesh).map_err(|source| SceneError::Mesh { mesh: k, source })?;
                Ok(SceneMesh {
                    centre: geometry.bounds().centre(),
                    bounds: geometry.bounds(),
                    sorter: MeshSorter::Bsp(Bsp::new(&geometry)),
                    mesh,
                })
            })
            .collect::<Result<Vec<_>, SceneError>>()?;
        let mut face_offsets = Vec::with_capacity(instances.len());
        let mut slots = Vec::with_capacity(instances.len());
        let mut faces = 0u32;
        for (k, instance) in instances.iter().enumerate() {
            let Some(mesh) = scene_meshes.get(instance.mesh) else {
                return Err(SceneError::NoSuchMesh {
                    instance: k,
                    mesh: instance.mesh,
                    meshes: scene_meshes.len(),
                });
            };
            check_transform(k, &instance.transform)?;
            let mut slot = mesh.mesh.face_count() as u32;
            for &(lod, _) in instance.lods.iter().flatten() {
                let Some(lod_mesh) = scene_meshes.get(lod) else {
                    return Err(SceneError::NoSuchMesh {
                        instance: k,
                        mesh: lod,
                        meshes: scene_meshes.len(),
                    });
                };
                slot = slot.max(lod_mesh.mesh.face_count() as u32);
            }
            face_offsets.push(faces);
            slots.push(slot);
            faces = faces.checked_add(slot).ok_or(SceneError::Mesh {
                mesh: scene_meshes.len(),
                source: MeshError::TooLarge,
            })?;
        }
        let boxes: Vec<Bounds> = instances
            .iter()
            .map(|i| world_box(&scene_meshes[i.mesh].bounds, &i.transform))
            .collect();
        let bounds = Bounds::from_points(instances.iter().flat_map(|i| {
            scene_meshes[i.mesh]
                .mesh
                .positions()
                .iter()
                .map(|&p| i.transform.transform_point3(p))
        }))
        .ok_or(SceneError::Empty)?;
        let billboards = instances
            .iter()
            .enumerate()
            .filter(|(_, i)| i.billboard)
            .map(|(k, i)| (k, i.transform))
            .collect();
        let active = instances.iter().map(|i| i.mesh).collect();
        let inverses = instances.iter().map(|i| i.transform.inverse()).collect();
        Ok(SceneSorter {
            meshes: scene_meshes,
            instances,
            billboards,
            slots,
            active,
            inverses,
            billboard_rotation: None,
            face_offsets,
            boxes,
            bounds,
            trees: [Vec::new(), Vec::new(), Vec::new()],
            tree_dirty: true,
            clusters: HashMap::new(),
            stats: SceneStats::default(),
            leaves: Vec::new(),
            stack: Vec::new(),
            members: Vec::new(),
            local: DrawList::new(),
            corners: Vec::new(),
            empty: Arc::new(PolygonSet::new()),
        })
    }

    /// Orders every mesh's instances by a [`Presorted`](crate::Presorted) of the mesh
    /// (built from [`Geometry::with_exact_corners`]) instead of its BSP: no ordering per
    /// frame and no extra items, for a build per mesh (quadratic in its pieces). Every
    /// instance shares its mesh's orders, the viewer mapped into the instance's frame
    /// (occlusion and facing are preserved by affine maps).
    ///
    /// # Errors
    /// The first mesh whose build stops ([`PresortError`](crate::PresortError)); meshes
    /// before it keep their new sorters.
    pub fn presort_meshes(
        &mut self,
        options: &crate::PresortOptions,
    ) -> Result<(), crate::PresortError> {
        for mesh in &mut self.meshes {
            // The mesh was accepted by `Geometry::new`; with exact corners it only fans what
            // `new` snapped, so it is accepted too (else the BSP stays).
            if let Ok(geometry) = Geometry::with_exact_corners(&mesh.mesh) {
                let presorted = crate::Presorted::try_new(&geometry, options)?;
                mesh.sorter = MeshSorter::Presorted(Box::new(presorted));
            }
        }
        Ok(())
    }

    /// The scene's frame of reference, a world box: fit views to it (its centre is the
    /// origin of the draw lists' centred coordinates). The instances' vertices when the
    /// scene was made, unless set by [`set_bounds`](Self::set_bounds).
    #[must_use]
    pub fn bounds(&self) -> Bounds {
        self.bounds
    }

    /// Sets the frame of reference, e.g. a box that holds every instance wherever it moves
    /// (then [`flattened`](Self::flattened) keeps the same centre frame after frame).
    pub fn set_bounds(&mut self, bounds: Bounds) {
        self.bounds = bounds;
    }

    /// The instances.
    #[must_use]
    pub fn instances(&self) -> &[Instance] {
        &self.instances
    }

    /// Moves instance `instance`: the coarse order is rebuilt at the next frame, and the
    /// clusters it belongs to; nothing of the other instances is.
    pub fn set_transform(
        &mut self,
        instance: usize,
        transform: DAffine3,
    ) -> Result<(), SceneError> {
        check_transform(instance, &transform)?;
        if let Some(entry) = self.billboards.iter_mut().find(|(k, _)| *k == instance) {
            entry.1 = transform;
            // Placed for the current view at the next frame.
            self.billboard_rotation = None;
            return Ok(());
        }
        self.place(instance, transform)
    }

    /// Picks each instance's level of detail by the size of its own mesh's box in the image;
    /// a change invalidates what depends on the instance.
    fn choose_lods(&mut self, view: &View) {
        let centre = self.bounds.centre();
        for i in 0..self.instances.len() {
            let instance = self.instances[i];
            if instance.lods.iter().all(Option::is_none) {
                continue;
            }
            let size = projected_size(
                view,
                &world_box(&self.meshes[instance.mesh].bounds, &instance.transform),
                centre,
            );
            let chosen = instance
                .lods
                .iter()
                .flatten()
                .filter(|&&(_, below)| size < below)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map_or(instance.mesh, |&(mesh, _)| mesh);
            if chosen != self.active[i] {
                self.active[i] = chosen;
                self.boxes[i] = world_box(&self.meshes[chosen].bounds, &instance.transform);
                self.tree_dirty = true;
                self.clusters.retain(|members, _| !members.contains(&i));
            }
        }
    }

    /// Sets an instance's world transform and invalidates what depends on it.
    fn place(&mut self, instance: usize, transform: DAffine3) -> Result<(), SceneError> {
        let Some(slot) = self.instances.get_mut(instance) else {
            return Err(SceneError::NoSuchMesh {
                instance,
                mesh: usize::MAX,
                meshes: self.meshes.len(),
            });
        };
        slot.transform = transform;
        self.inverses[instance] = transform.inverse();
        self.boxes[instance] = world_box(&self.meshes[self.active[instance]].bounds, &transform);
        self.tree_dirty = true;
        self.clusters
            .retain(|members, _| !members.contains(&instance));
        Ok(())
    }

    /// What the last frame did.
    #[must_use]
    pub fn stats(&self) -> SceneStats {
        self.stats
    }

    /// The whole scene as one mesh in world space, faces numbered as the draw lists number
    /// them (instance by instance), a mirrored instance's faces reversed so that their
    /// winding gives their front. For references (the truth, the oracle) and for the
    /// flattening that the instance path replaces.
    #[must_use]
    pub fn flattened(&self) -> PolygonMesh {
        let (positions, faces) = world_faces(
            &self.meshes,
            &self.instances,
            &self.active,
            0..self.instances.len(),
            Some(&self.slots),
        );
        PolygonMesh::new(positions, faces).expect("instances of valid meshes are a valid mesh")
    }

    fn build_tree(&mut self) {
        for (layer, nodes) in Layer::ALL.iter().zip(&mut self.trees) {
            nodes.clear();
            let members: Vec<usize> = (0..self.instances.len())
                .filter(|&i| self.instances[i].layer == *layer)
                .collect();
            if !members.is_empty() {
                build(&self.boxes, members, nodes);
            }
        }
        self.tree_dirty = false;
        self.stats.tree_builds += 1;
    }

    /// The instance whose faces hold scene face `face` (the numbering of
    /// [`flattened`](Self::flattened)), e.g. for a render step's filter.
    #[must_use]
    pub fn instance_of_face(&self, face: u32) -> Option<usize> {
        let k = self.face_offsets.partition_point(|&first| first <= face);
        let i = k.checked_sub(1)?;
        (face - self.face_offsets[i] < self.slots[i]).then_some(i)
    }

    /// The material override of the instance that holds scene face `face`, if it has one.
    #[must_use]
    pub fn material_of_face(&self, face: u32) -> Option<u32> {
        self.instances[self.instance_of_face(face)?].material
    }

    /// Leaves of layer `layer`'s tree in drawing order (far to near) for a viewer in world
    /// coordinates.
    fn order_leaves(&mut self, layer: usize, viewer: Viewer) {
        self.leaves.clear();
        let nodes = &self.trees[layer];
        if nodes.is_empty() {
            return;
        }
        let stack = &mut self.stack;
        stack.clear();
        stack.push(0);
        while let Some(n) = stack.pop() {
            match &nodes[n] {
                Node::Leaf(_) => self.leaves.push(n),
                &Node::Split {
                    axis,
                    at,
                    below,
                    above,
                } => {
                    // The side holding the viewer is nearer: drawn last, so pushed first.
                    let viewer_above = match viewer {
                        Viewer::Eye(e) => e[axis] >= at,
                        Viewer::Direction(d) => d[axis] >= 0.0,
                    };
                    if viewer_above {
                        stack.extend([above, below]);
                    } else {
                        stack.extend([below, above]);
                    }
                }
            }
        }
    }
}

impl FaceSorter for SceneSorter {
    fn name(&self) -> &'static str {
        "scene"
    }

    /// `view` must be fitted to [`bounds`](SceneSorter::bounds) (its centre is the scene's).
    fn sort(&mut self, view: &View, out: &mut DrawList) {
        if !self.billboards.is_empty() && self.billboard_rotation != Some(view.rotation()) {
            let facing = view.rotation().transpose();
            for k in 0..self.billboards.len() {
                let (i, placement) = self.billboards[k];
                let world = DAffine3::from_mat3_translation(
                    facing * placement.matrix3,
                    placement.translation,
                );
                // A rotation of a valid placement stays valid.
                let _ = self.place(i, world);
            }
            self.billboard_rotation = Some(view.rotation());
        }
        self.choose_lods(view);
        if self.tree_dirty {
            self.build_tree();
        }
        let centre = self.bounds.centre();
        let cull = view.cull_test();
        let world_viewer = match cull.viewer {
            Viewer::Eye(e) => Viewer::Eye(e + centre),
            d @ Viewer::Direction(_) => d,
        };
        out.begin(&self.empty);
        let mut drawn = 0;
        let mut culled = 0;
        let mut clusters = 0;
        for layer in 0..Layer::ALL.len() {
            self.order_leaves(layer, world_viewer);
            let leaves = std::mem::take(&mut self.leaves);
            let mut members = std::mem::take(&mut self.members);
            for &leaf in &leaves {
                let Node::Leaf(all) = &self.trees[layer][leaf] else {
                    continue;
                };
                members.clear();
                for &i in all {
                    if box_in_image(view, &self.boxes[i], centre) {
                        members.push(i);
                    } else {
                        culled += 1;
                    }
                }
                drawn += members.len();
                match members.as_slice() {
                    [] => {}
                    &[one] => self.draw_instance(one, &cull, centre, out),
                    _ => {
                        clusters += 1;
                        self.draw_cluster(&members, view, out);
                    }
                }
            }
            self.leaves = leaves;
            self.members = members;
        }
        self.stats.objects_drawn = drawn;
        self.stats.objects_culled = culled;
        self.stats.clusters = clusters;
    }
}

impl SceneSorter {
    /// One instance by its mesh's own BSP, the viewer mapped into the mesh's frame.
    fn draw_instance(&mut self, index: usize, cull: &CullTest, centre: DVec3, out: &mut DrawList) {
        let instance = self.instances[index];
        let mesh = &mut self.meshes[self.active[index]];
        // World-centred → mesh-centred: x_l = T⁻¹(x + c_w) − c_l.
        let to_local = DAffine3::from_translation(-mesh.centre)
            * self.inverses[index]
            * DAffine3::from_translation(centre);
        let to_world = to_local.inverse();
        mesh.sorter
            .sort_culled(&cull.transformed(&to_local), &mut self.local);
        let mirrored = instance.transform.matrix3.determinant() < 0.0;
        let offset = self.face_offsets[index];
        // A plane n·x = o in the mesh's frame is (Aᵀn)·x = o − n·b in the scene's, for
        // x_local = A·x + b; a mirrored instance's corners are reversed, and so its normal.
        let normals = to_local.matrix3.transpose();
        let side = if mirrored { -1.0 } else { 1.0 };
        for item in self.local.items() {
            self.corners.clear();
            self.corners.extend(
                self.local
                    .corners(*item)
                    .iter()
                    .map(|&p| to_world.transform_point3(p)),
            );
            if mirrored {
                self.corners.reverse();
            }
            let local = self.local.plane(*item);
            let normal = normals * local.normal() * side;
            if let Some(plane) = Plane::try_from_point_normal(self.corners[0], normal) {
                let polygon = out.add_frame_polygon(&self.corners, offset + item.face, plane);
                out.push(polygon, offset + item.face);
            }
        }
    }

    /// Interlocking instances ordered together (module docs): Newell while the cluster is
    /// new, one BSP over their world faces once it has stayed unchanged.
    fn draw_cluster(&mut self, members: &[usize], view: &View, out: &mut DrawList) {
        if !self.clusters.contains_key(members) {
            let (positions, faces) = world_faces(
                &self.meshes,
                &self.instances,
                &self.active,
                members.iter().copied(),
                None,
            );
            let mut scene_faces = Vec::new();
            for &m in members {
                let n = self.meshes[self.active[m]].mesh.face_count() as u32;
                scene_faces.extend(self.face_offsets[m]..self.face_offsets[m] + n);
            }
            let mesh = PolygonMesh::new(positions, faces)
                .expect("instances of valid meshes are a valid mesh");
            // Centred like the scene; tolerances relative to the scene's size.
            let Ok(geometry) = Geometry::new_in_frame(&mesh, self.bounds) else {
                return;
            };
            self.stats.cluster_builds += 1;
            self.clusters.insert(
                members.to_vec(),
                Cluster {
                    // Made again each frame a member moves: no edge neighbours to find.
                    sorter: ClusterSorter::Newell(Box::new(crate::Newell::without_coverage(
                        &geometry,
                    ))),
                    geometry,
                    frames: 0,
                    faces: scene_faces,
                },
            );
        }
        let Some(cluster) = self.clusters.get_mut(members) else {
            return;
        };
        cluster.frames += 1;
        if cluster.frames == SETTLED_FRAMES
            && let ClusterSorter::Newell(_) = cluster.sorter
        {
            cluster.sorter = ClusterSorter::Bsp(Bsp::new(&cluster.geometry));
            self.stats.cluster_trees += 1;
        }
        match &mut cluster.sorter {
            ClusterSorter::Newell(newell) => newell.sort(view, &mut self.local),
            ClusterSorter::Bsp(bsp) => bsp.sort(view, &mut self.local),
        }
        for item in self.local.items() {
            let face = cluster.faces[item.face as usize];
            let polygon =
                out.add_frame_polygon(self.local.corners(*item), face, *self.local.plane(*item));
            out.push(polygon, face);
        }
    }
}

/// The world positions and faces of some instances (a mirrored one's faces reversed).
/// `active[k]` is the mesh instance `k` draws; with `pad`, each instance's faces are padded
/// with degenerate faces (no area: no pieces) up to its slot, so that face numbers match the
/// draw lists'.
fn world_faces(
    meshes: &[SceneMesh],
    instances: &[Instance],
    active: &[usize],
    which: impl Iterator<Item = usize>,
    pad: Option<&[u32]>,
) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for k in which {
        let instance = &instances[k];
        let mesh = &meshes[active[k]].mesh;
        let first = positions.len() as u32;
        positions.extend(
            mesh.positions()
                .iter()
                .map(|&p| instance.transform.transform_point3(p)),
        );
        let mirrored = instance.transform.matrix3.determinant() < 0.0;
        for face in mesh.faces() {
            let mut f: Vec<u32> = face.iter().map(|&i| first + i).collect();
            if mirrored {
                f.reverse();
            }
            faces.push(f);
        }
        if let Some(slots) = pad {
            for _ in mesh.face_count() as u32..slots[k] {
                faces.push(vec![first; 3]);
            }
        }
    }
    (positions, faces)
}

fn check_transform(instance: usize, t: &DAffine3) -> Result<(), SceneError> {
    let det = t.matrix3.determinant();
    if !t.is_finite() || det == 0.0 || !det.is_finite() {
        return Err(SceneError::SingularTransform { instance });
    }
    Ok(())
}

/// The eight corners of a box.
fn box_corners(b: &Bounds) -> [DVec3; 8] {
    std::array::from_fn(|k| {
        DVec3::new(
            if k & 1 == 0 { b.min.x } else { b.max.x },
            if k & 2 == 0 { b.min.y } else { b.max.y },
            if k & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

/// The world box of a local box under a transform (its eight corners').
fn world_box(local: &Bounds, t: &DAffine3) -> Bounds {
    Bounds::from_points(box_corners(local).map(|p| t.transform_point3(p))).unwrap_or(*local)
}

/// Whether any of a world box can show in the image: `false` only when all its corners
/// are in front of the near plane and beyond one side of the image.
fn box_in_image(view: &View, b: &Bounds, centre: DVec3) -> bool {
    let (w, h) = (f64::from(view.width()), f64::from(view.height()));
    let mut out = [true; 4];
    for p in box_corners(b) {
        let Some(s) = view.project_view_point(view.to_view(p - centre)) else {
            return true;
        };
        out[0] &= s.x < 0.0;
        out[1] &= s.x > w;
        out[2] &= s.y < 0.0;
        out[3] &= s.y > h;
    }
    !out.iter().any(|&o| o)
}

/// The diagonal (pixels) of a world box's projection; infinite when a corner is behind the
/// near plane.
fn projected_size(view: &View, b: &Bounds, centre: DVec3) -> f64 {
    let mut lo = glam::DVec2::INFINITY;
    let mut hi = glam::DVec2::NEG_INFINITY;
    for p in box_corners(b) {
        let Some(s) = view.project_view_point(view.to_view(p - centre)) else {
            return f64::INFINITY;
        };
        lo = lo.min(s);
        hi = hi.max(s);
    }
    lo.distance(hi)
}

/// Builds the coarse tree over `items` (instance indices) into `nodes`; returns its index.
fn build(boxes: &[Bounds], mut items: Vec<usize>, nodes: &mut Vec<Node>) -> usize {
    let here = nodes.len();
    nodes.push(Node::Leaf(Vec::new()));
    if items.len() < 2 {
        nodes[here] = Node::Leaf(items);
        return here;
    }
    // The separating plane nearest the middle, on any axis: sorted by their low side, a
    // split after position k works when no box before it reaches past the next one's low
    // side.
    let mut best: Option<(usize, usize, f64, usize)> = None; // (imbalance, axis, at, k)
    let n = items.len();
    for axis in 0..3 {
        items.sort_by(|&a, &b| boxes[a].min[axis].total_cmp(&boxes[b].min[axis]));
        let mut reach = f64::NEG_INFINITY;
        for k in 0..n - 1 {
            reach = reach.max(boxes[items[k]].max[axis]);
            let next = boxes[items[k + 1]].min[axis];
            if reach <= next {
                let imbalance = (k + 1).abs_diff(n - k - 1);
                if best.is_none_or(|b| imbalance < b.0) {
                    best = Some((imbalance, axis, 0.5 * (reach + next), k));
                }
            }
        }
    }
    let Some((_, axis, at, k)) = best else {
        items.sort_unstable();
        nodes[here] = Node::Leaf(items);
        return here;
    };
    items.sort_by(|&a, &b| boxes[a].min[axis].total_cmp(&boxes[b].min[axis]));
    let above_items = items.split_off(k + 1);
    let below = build(boxes, items, nodes);
    let above = build(boxes, above_items, nodes);
    nodes[here] = Node::Split {
        axis,
        at,
        below,
        above,
    };
    here
}
