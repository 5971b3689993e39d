//! The scene a command renders: a scene file or one OBJ, with the command line's flags applied, then
//! checked. Every bad value is reported with where it came from: the flag that set it, or the scene
//! file's line and column, or the framing of an `--obj`.

use super::args::{OnOff, SceneArgs};
use crate::res::ResDirs;
use crate::scene::{Issue, SceneDesc, SceneFile};
use anyhow::{bail, Context as _, Result};
use rust_i18n::t;

/// Where the scene's values came from, for messages.
enum Origin {
    File(Box<SceneFile>),
    /// `--obj`: the OBJ's path; the camera is framed from its bounds.
    Obj(String),
}

/// Keys set by the flags given, with the flag's name ("camera.near" -> "--near").
type FlagKeys = Vec<(&'static str, &'static str)>;

/// Loads the scene the arguments describe, with overrides applied and checked.
pub fn load_scene(args: &SceneArgs, res: &ResDirs) -> Result<SceneDesc> {
    let (mut desc, origin, model) = if let Some(obj) = &args.obj {
        let path = obj
            .canonicalize()
            .with_context(|| t!("render.obj_not_found", path = obj.display()))?;
        let data = crate::gl::mesh::MeshData::load_model(&path)?;
        let desc = SceneDesc::single_obj(&path);
        (desc, Origin::Obj(path.display().to_string()), Some(data))
    } else {
        let path = match &args.scene {
            Some(p) => p.clone(),
            None => res
                .find("scenes/demo.toml")
                .map_err(|e| anyhow::anyhow!("{e}"))?,
        };
        let file = SceneFile::read(&path)?;
        check_meshes(&file, res)?;
        (file.desc.clone(), Origin::File(Box::new(file)), None)
    };
    let flags = apply_flags(args, &mut desc)?;
    // The keys neither the scene file nor a flag wrote: the method's recommended configuration.
    crate::scene::ao_defaults::apply(&mut desc.ao);
    if let Some(mesh) = &model {
        frame_mesh(&mut desc, mesh, args);
    }
    for w in desc.clamp_values() {
        let message = describe(&w, &origin, &flags);
        eprintln!("{}", t!("render.warning", message = message));
    }
    let errors = desc.errors();
    if !errors.is_empty() {
        let lines: Vec<String> = errors
            .iter()
            .map(|e| describe(e, &origin, &flags))
            .collect();
        bail!("{}", lines.join("\n"));
    }
    Ok(desc)
}

/// Every object's mesh is found: one that is not is an error at its line of the scene file, naming
/// the folders searched (beside the scene file, then `Res/`); a folder or a broken link standing at
/// the name is named as such.
fn check_meshes(file: &SceneFile, res: &ResDirs) -> Result<()> {
    let folder = match file.path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    for (i, o) in file.desc.objects.iter().enumerate() {
        let place = file
            .place(&format!("object[{i}].mesh"))
            .unwrap_or_else(|| file.path.display().to_string());
        let mesh = std::path::Path::new(&o.mesh);
        if let Some(what) = crate::res::blocking_entry(&folder.join(mesh)) {
            bail!("{place}: {what}");
        }
        let Err(e) = file.desc.mesh_path(&o.mesh, res) else {
            continue;
        };
        if let Some(what) = e.blocked {
            bail!("{place}: {what}");
        }
        let beside = std::path::absolute(folder).unwrap_or_else(|_| folder.to_path_buf());
        let searched = format!("{}, {}", beside.display(), e.searched);
        let message = t!(
            "scene.mesh_not_found",
            place = place,
            mesh = o.mesh,
            searched = searched
        );
        bail!("{message}");
    }
    Ok(())
}

/// One issue with its source: "--near 1e-30: ...", "FILE:LINE:COL: camera.near = 1e-30: ...".
fn describe(issue: &Issue, origin: &Origin, flags: &FlagKeys) -> String {
    let flag = flags
        .iter()
        .find(|(key, _)| issue.key == *key || issue.key.starts_with(&format!("{key}[")));
    if let Some((_, flag)) = flag {
        return format!("{flag} {}: {}", issue.value, issue.message);
    }
    match origin {
        Origin::File(file) => file.describe(issue),
        Origin::Obj(path) if issue.key.starts_with("camera.") => {
            format!("{issue} (framed from the bounds of {path})")
        }
        Origin::Obj(path) => format!("{issue} (default for --obj {path})"),
    }
}

/// Frames the model (`scene::framing`), keeping what the flags set, and says which AO radius it
/// chose and at what scale it draws the model.
fn frame_mesh(desc: &mut SceneDesc, mesh: &crate::gl::mesh::MeshData, args: &SceneArgs) {
    let fixed = crate::scene::framing::Fixed {
        eye: args.eye.is_some(),
        target: args.target.is_some(),
        near: args.near.is_some(),
        far: args.far.is_some(),
        radius: args.radius.is_some(),
    };
    let Some(framed) = crate::scene::framing::frame_mesh(desc, mesh, fixed) else {
        return;
    };
    let size = format!("{:.4}", framed.size);
    if framed.scale != 1.0 {
        let scale = framed.scale;
        eprintln!("{}", t!("render.obj_scaled", size = size, scale = scale));
    }
    if let Some(radius) = framed.radius {
        eprintln!(
            "{}",
            t!("render.obj_radius", radius = radius, diagonal = size)
        );
    }
}

/// Applies the flags given and returns the keys they set; range checks of flags without a scene key
/// happen here.
fn apply_flags(args: &SceneArgs, desc: &mut SceneDesc) -> Result<FlagKeys> {
    let mut keys = FlagKeys::new();
    let c = &mut desc.camera;
    if let Some(v) = args.eye {
        c.eye = v.to_array();
        keys.push(("camera.eye", "--eye"));
    }
    if let Some(v) = args.target {
        c.target = v.to_array();
        keys.push(("camera.target", "--target"));
    }
    if let Some(v) = args.fov {
        c.fov_y = v;
        keys.push(("camera.fov_y", "--fov"));
    }
    if let Some(v) = args.near {
        c.near = v;
        keys.push(("camera.near", "--near"));
    }
    if let Some(v) = args.far {
        c.far = v;
        keys.push(("camera.far", "--far"));
    }
    if let Some(w) = args.width {
        desc.output.width = w;
        keys.push(("output.width", "--width"));
    }
    if let Some(h) = args.height {
        desc.output.height = h;
        keys.push(("output.height", "--height"));
    }
    if let Some(d) = args.depth {
        desc.output.depth = d;
    }
    if let Some(ao) = args.ao {
        desc.ao.enabled = ao == OnOff::On;
    }
    if let Some(m) = args.method {
        desc.ao.method = m;
    }
    if let Some(n) = args.samples {
        if n == 0 || n > 256 {
            bail!("{}", t!("render.bad_samples", n = n));
        }
        desc.ao.samples = n;
        // An explicit count wins over a preset from the scene file or the recommendation.
        desc.ao.quality = None;
        desc.ao.written.quality = true;
    }
    if let Some(q) = args.quality {
        desc.ao.quality = Some(q);
        desc.ao.written.quality = true;
    }
    if let Some(n) = args.rays_per_pixel {
        let (lo, hi) = crate::ao::settings::RAYS_RANGE;
        if !(lo..=hi).contains(&n) {
            bail!("{}", t!("render.bad_rays", n = n, max = hi));
        }
        desc.ao.rays = n;
        desc.ao.written.rays = true;
    }
    if let Some(n) = args.accumulate {
        let (lo, hi) = crate::ao::settings::ACCUMULATE_RANGE;
        if !(lo..=hi).contains(&n) {
            bail!("{}", t!("render.bad_accumulate", n = n, max = hi));
        }
        desc.ao.accumulate = n;
    }
    if let Some(c) = args.composite {
        desc.ao.composite = c;
    }
    if let Some(t) = args.tint {
        if t.min_element() < 0.0 || t.max_element() > 1.0 {
            bail!("{}", t!("render.bad_tint", tint = t));
        }
        desc.ao.tint = t.to_array();
        keys.push(("ao.tint", "--tint"));
    }
    if let Some(p) = args.power {
        if !(p.is_finite() && (0.05..=20.0).contains(&p)) {
            bail!("{}", t!("render.bad_power", power = p));
        }
        desc.ao.power = p;
        keys.push(("ao.power", "--power"));
    }
    if let Some(r) = args.radius {
        if !(r.is_finite() && r > 0.0 && r <= 100.0) {
            bail!("{}", t!("render.bad_radius", radius = r));
        }
        desc.ao.radius = r;
        keys.push(("ao.radius", "--radius"));
    }
    if let Some(r) = args.ao_resolution {
        desc.ao.resolution = r;
        desc.ao.written.resolution = true;
    }
    if let Some(n) = args.normals {
        desc.ao.normals = n;
        desc.ao.written.normals = true;
    }
    if let Some(g) = args.guard_band {
        desc.ao.guard_band = g;
        desc.ao.written.guard_band = true;
    }
    if let Some(l) = args.layers {
        desc.ao.layers = l;
        desc.ao.written.layers = true;
    }
    if let Some(h) = args.slab_hierarchy {
        desc.ao.slab_hierarchy = h;
    }
    if let Some(t) = args.thickness {
        let (lo, hi) = crate::ao::settings::THICKNESS_RANGE;
        if let crate::ao::Thickness::Metres(m) = t {
            if !(m.is_finite() && (lo..=hi).contains(&m)) {
                bail!(
                    "--thickness {m}: use a thickness in metres between {lo} and {hi}, or backface"
                );
            }
        }
        desc.ao.thickness = Some(t);
        desc.ao.written.thickness = true;
        keys.push(("ao.thickness", "--thickness"));
    }
    Ok(keys)
}

/// Runs `--method-file`'s method in `engine` (its errors name the file, and the line).
pub fn use_method_file(
    engine: &mut crate::render::Engine,
    file: Option<&std::path::Path>,
) -> Result<()> {
    if let Some(path) = file {
        let file = crate::scene::method_file::MethodFile::read(path)?;
        engine.use_method_file(file)?;
    }
    Ok(())
}
