//! The scene walk: mesh-carrying node instances with world matrices, with
//! the node depth, visit count and cycles checked. The walk is iterative, so
//! a caller-raised depth limit cannot overflow the stack.

use glam::DMat4;
use gltf::{Document, Node};

use super::gltf_err;
use crate::{LoadError, LoadOptions};

/// Mesh-carrying node instances of the scene, depth first (pre-order), with
/// world matrices. The scene is the default scene, else scene 0, else every
/// node that is nobody's child.
pub(super) fn walk_scene<'a>(
    doc: &'a Document,
    file: &str,
    options: &LoadOptions,
) -> Result<Vec<(Node<'a>, DMat4)>, LoadError> {
    let roots: Vec<Node<'a>> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            let mut is_child = vec![false; doc.nodes().len()];
            for node in doc.nodes() {
                for child in node.children() {
                    if let Some(c) = is_child.get_mut(child.index()) {
                        *c = true;
                    }
                }
            }
            doc.nodes()
                .filter(|n| !is_child.get(n.index()).copied().unwrap_or(true))
                .collect()
        }
    };
    enum Step<'a> {
        Enter(Node<'a>, DMat4),
        Leave,
    }
    let mut out = Vec::new();
    // Indices of the nodes from the root to the current one.
    let mut path: Vec<usize> = Vec::new();
    let mut on_path = vec![false; doc.nodes().len()];
    let mut visits = 0usize;
    let mut stack: Vec<Step<'a>> = roots
        .into_iter()
        .rev()
        .map(|n| Step::Enter(n, DMat4::IDENTITY))
        .collect();
    while let Some(step) = stack.pop() {
        let (node, parent) = match step {
            Step::Enter(node, parent) => (node, parent),
            Step::Leave => {
                if let Some(i) = path.pop()
                    && let Some(flag) = on_path.get_mut(i)
                {
                    *flag = false;
                }
                continue;
            }
        };
        let index = node.index();
        if on_path.get(index).copied().unwrap_or(false) {
            return Err(gltf_err(
                file,
                format!("node {index} is its own ancestor (cycle through nodes {path:?})"),
            ));
        }
        if path.len() >= options.max_node_depth {
            return Err(gltf_err(
                file,
                format!(
                    "node hierarchy deeper than the limit {} at node {index}",
                    options.max_node_depth
                ),
            ));
        }
        visits += 1;
        if visits > options.max_node_visits {
            return Err(LoadError::TooLarge {
                file: file.to_owned(),
                what: "node visits in the glTF scene walk",
                actual: visits as u64,
                limit: options.max_node_visits as u64,
            });
        }
        let local = node.transform().matrix();
        let local = DMat4::from_cols_array_2d(&local.map(|c| c.map(f64::from)));
        if !local.is_finite() {
            return Err(gltf_err(
                file,
                format!("node {index} has a non-finite transform"),
            ));
        }
        let world = parent * local;
        if node.mesh().is_some() || node.camera().is_some() {
            out.push((node.clone(), world));
        }
        path.push(index);
        if let Some(flag) = on_path.get_mut(index) {
            *flag = true;
        }
        stack.push(Step::Leave);
        let children: Vec<Node<'a>> = node.children().collect();
        stack.extend(children.into_iter().rev().map(|c| Step::Enter(c, world)));
    }
    Ok(out)
}
