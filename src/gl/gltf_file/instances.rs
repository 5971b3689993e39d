//! The instance transforms of `EXT_mesh_gpu_instancing`: per instance a translation, a rotation
//! (unit quaternion x, y, z, w) and a scale, each from an accessor of its own (a missing one is the
//! identity), composed as a node's TRS is, T * R * S, inside the node's space.

use super::buffers::check_accessor;
use super::document::Instancing;
use anyhow::{bail, Result};
use glam::{Mat4, Quat, Vec3};
use gltf::accessor::{DataType, Dimensions};
use rust_i18n::t;

/// The transform of every instance of node `node`.
pub fn read(
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    attrs: &Instancing,
    node: usize,
    shown: &str,
) -> Result<Vec<Mat4>> {
    let translation =
        vectors::<[f32; 3]>(doc, buffers, attrs.translation, "TRANSLATION", node, shown)?;
    let rotation = vectors::<[f32; 4]>(doc, buffers, attrs.rotation, "ROTATION", node, shown)?;
    let scale = vectors::<[f32; 3]>(doc, buffers, attrs.scale, "SCALE", node, shown)?;
    let counts: Vec<usize> = [
        translation.as_ref().map(Vec::len),
        rotation.as_ref().map(Vec::len),
        scale.as_ref().map(Vec::len),
    ]
    .into_iter()
    .flatten()
    .collect();
    let Some(&count) = counts.first() else {
        return Ok(vec![Mat4::IDENTITY]); // no geometric attribute: one instance where the node is
    };
    if counts.iter().any(|&c| c != count) {
        let counts = format!("{counts:?}");
        let message = t!(
            "gltf.instance_counts",
            path = shown,
            index = node,
            counts = counts
        );
        bail!("{message}");
    }
    Ok((0..count)
        .map(|i| {
            let t = translation
                .as_ref()
                .map_or(Vec3::ZERO, |v| Vec3::from(v[i]));
            let r = rotation
                .as_ref()
                .map_or(Quat::IDENTITY, |v| Quat::from_array(v[i]).normalize());
            let s = scale.as_ref().map_or(Vec3::ONE, |v| Vec3::from(v[i]));
            Mat4::from_scale_rotation_translation(s, r, t)
        })
        .collect())
}

/// The float vectors of accessor `index` (`None` when the attribute is absent).
fn vectors<T: gltf::accessor::Item + Copy>(
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    index: Option<usize>,
    name: &str,
    node: usize,
    shown: &str,
) -> Result<Option<Vec<T>>> {
    let Some(index) = index else {
        return Ok(None);
    };
    let Some(acc) = doc.accessors().nth(index) else {
        let message = t!(
            "gltf.instance_attribute",
            path = shown,
            index = node,
            name = name
        );
        bail!("{message}");
    };
    let dims = match std::mem::size_of::<T>() / 4 {
        4 => Dimensions::Vec4,
        _ => Dimensions::Vec3,
    };
    check_accessor(&acc, buffers, &[DataType::F32], dims, name, shown)?;
    let iter = gltf::accessor::Iter::<T>::new(acc, |b| buffers.get(b.index()).map(Vec::as_slice));
    Ok(Some(iter.map(Iterator::collect).unwrap_or_default()))
}
