//! The grading rig: one headless GL context holding the project's passes and the student's side by
//! side, the student's built from a private copy of the graded file, and what a step hands back.

use super::picture::Panel;
use super::say::say;
use crate::ao::{AoSettings, SaoLesson};
use crate::gl::{FramebufferObject, Gl, MeshBuffer, ProgramError, Texture, TextureDesc};
use crate::i18n::Text;
use crate::math::Camera;
use crate::platform::headless::{DevicePreference, HeadlessContext};
use crate::res::ResDirs;
use anyhow::Result;
use std::collections::BTreeMap;
use std::path::Path;
use std::rc::Rc;

/// The metric in which a step reports the fraction of its outputs that are NaN or Inf (what a
/// shader that reads none of its inputs may write: see `run_step`).
pub const NONFINITE_METRIC: &str = "nonfinite_fraction";

/// The outcome of one step.
pub struct Verdict {
    pub passed: bool,
    /// What the student reads, in English and the chosen language (`grade.verdict.*` keys).
    pub message: Text,
    pub metrics: BTreeMap<String, f64>,
    pub panels: Vec<Panel>,
    /// The sub-steps' verdicts, for a step graded in parts (`points::parts_of`); empty otherwise.
    pub parts: Vec<PartVerdict>,
}

/// One sub-step's outcome.
pub struct PartVerdict {
    /// `points::SAO_PARTS`'s id.
    pub id: &'static str,
    pub passed: bool,
    pub message: Text,
    /// The number in appendix A of the course's erratum that the shader keeps, when that is why
    /// the sub-step fails.
    pub erratum: Option<u32>,
}

impl Verdict {
    pub fn fail(message: Text) -> Verdict {
        Verdict {
            passed: false,
            message,
            metrics: BTreeMap::new(),
            panels: Vec::new(),
            parts: Vec::new(),
        }
    }
    /// A failure of the grader itself (not of the student's shader).
    pub fn grader_error(e: &anyhow::Error) -> Verdict {
        let error = format!("{e:#}");
        Verdict::fail(say!("grade.verdict.grader_error", error = error))
    }
}

/// The project's passes and the student's, sharing one GL context.
pub struct Rig {
    pub gl: Gl,
    pub meshes: MeshBuffer,
    pub reference: SaoLesson,
    pub student: SaoLesson,
    /// Declared last so that it is dropped last: the GL objects above are deleted while it is current.
    _context: HeadlessContext,
}

/// Where the graded file comes from, for messages.
pub struct Subject<'a> {
    /// Folder the student's file was copied into (searched first).
    pub work_dir: &'a Path,
    /// Folder the file really lives in (shown in messages instead of `work_dir`).
    pub shown_dir: &'a Path,
}

impl Rig {
    /// The project's SAO and the student's, on the same camera and depth (`passes::run_sao_pair`).
    pub fn sao_pair(
        &self,
        camera: &Camera,
        depth: &[f32],
        params: &AoSettings,
    ) -> Result<(Vec<f32>, Vec<f32>)> {
        super::passes::run_sao_pair(
            &self.reference,
            &self.student,
            &self.meshes,
            camera,
            depth,
            params,
        )
    }
}

impl Subject<'_> {
    /// Replaces the private copy's path by the student's in an error message.
    fn rewrite(&self, msg: &str) -> String {
        msg.replace(
            &self.work_dir.display().to_string(),
            &self.shown_dir.display().to_string(),
        )
    }
}

fn context() -> Result<HeadlessContext> {
    // Mesa's software device first: grading must not depend on the GPU, and a shader that never
    // ends must not hang a real one.
    HeadlessContext::with_preference(DevicePreference::Software).or_else(|_| HeadlessContext::new())
}

/// Replaces the R8 SAO and blur targets by R32F ones of the same size, so that an output that is
/// not normalised shows its real size instead of being clamped to 1.
pub fn float_targets(gl: &Gl, lesson: &mut SaoLesson) -> Result<()> {
    let (w, h) = lesson.targets.tex_depth.size_at(0);
    let make = |name: &str| -> Result<FramebufferObject> {
        let t = Rc::new(Texture::new(
            gl,
            TextureDesc::target(name, w, h, glow::R32F),
        )?);
        FramebufferObject::new(gl, Some(t), None, 0, 0)
    };
    lesson.targets.fbo_sao = make("grade sao")?;
    lesson.targets.fbo_blur = make("grade blur")?;
    Ok(())
}

/// A one-line message for a shader that does not build, naming the student's file (not the copy).
fn build_error_message(e: &anyhow::Error, subject: &Subject) -> Text {
    match e.downcast_ref::<ProgramError>() {
        Some(ProgramError::Compile { messages, .. }) => {
            // The compiler's own lines stay as they are (file:line: message); only ours is translated.
            let mut errors = messages
                .iter()
                .take(3)
                .cloned()
                .collect::<Vec<_>>()
                .join(" | ");
            if messages.len() > 3 {
                errors = format!("{errors} | … ({} more)", messages.len() - 3);
            }
            let errors = subject.rewrite(&errors);
            say!("grade.verdict.does_not_compile", errors = errors)
        }
        Some(ProgramError::Link { log, .. }) => {
            let log = subject.rewrite(&log.replace('\n', " | "));
            say!("grade.verdict.does_not_link", log = log)
        }
        Some(ProgramError::IncludeCycle {
            path,
            line,
            name,
            target,
        }) => {
            let at = subject.rewrite(&format!("{path}:{line}"));
            let target = subject.rewrite(target);
            say!(
                "grade.verdict.include_cycle",
                at = at,
                name = name,
                target = target
            )
        }
        Some(other) => {
            // Already a sentence naming the file and line (an #include refused, a file too big).
            let error = subject.rewrite(&other.to_string());
            say!("grade.verdict.build_refused", error = error)
        }
        None => {
            let error = subject.rewrite(&format!("{e:#}"));
            say!("grade.verdict.cannot_build", error = error)
        }
    }
}

/// Builds the project's passes from `project_res` and the student's from `subject.work_dir` (falling
/// back to the project's for the other files), for a main image of `main_w`×`main_h`. A student's
/// shader that does not build is the step's failing verdict; anything else is a grader error.
pub fn build_rig(
    subject: &Subject,
    project_res: &Path,
    (main_w, main_h): (u32, u32),
    camera: &Camera,
    params: &AoSettings,
) -> std::result::Result<Rig, Box<Verdict>> {
    let internal = |what: &str, e: anyhow::Error| {
        let error = format!("{e:#}");
        Box::new(Verdict::fail(say!(
            "grade.verdict.grader_error_in",
            what = what,
            error = error
        )))
    };
    let context = context().map_err(|e| internal("no OpenGL 4.5 context", e))?;
    let gl = context.gl.clone();
    let reference_res = ResDirs::only(vec![project_res.to_path_buf()]);
    let mut reference = SaoLesson::new(&gl, &reference_res, main_w, main_h, camera, params)
        .map_err(|e| internal("the project's own shaders do not build", e))?;
    let student_res = ResDirs::only(vec![
        subject.work_dir.to_path_buf(),
        project_res.to_path_buf(),
    ]);
    let mut student = SaoLesson::new(&gl, &student_res, main_w, main_h, camera, params)
        .map_err(|e| Box::new(Verdict::fail(build_error_message(&e, subject))))?;
    float_targets(&gl, &mut reference).map_err(|e| internal("targets", e))?;
    float_targets(&gl, &mut student).map_err(|e| internal("targets", e))?;
    let meshes = MeshBuffer::new(&gl).map_err(|e| internal("meshes", e))?;
    Ok(Rig {
        gl,
        meshes,
        reference,
        student,
        _context: context,
    })
}
