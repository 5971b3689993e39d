//! The grader: `opengl3d grade` renders fixed test inputs with a student's shaders and checks each of
//! the lesson's five shaders, one verdict per step.
//!
//! | step | file | checked against |
//! |---|---|---|
//! | `restore` | `sao_restore_depth.frag` | the exact (f64) inverse of the projection of the nearest of each 2×2 block, within float precision |
//! | `down-sampling` | `sao_down_sampling.frag` | the exact min of each 2×2 block, level by level |
//! | `simple` | `simple.frag` | the project's `Res/simple.frag`: an RGBA texture drawn at twice its size, every channel as `texture()` gives it, and the lesson's composite over an image |
//! | `sao` | `sao.frag` | the project's `Res/sao.frag` on the same mip chain (240×160): mean, 8×8 block RMSE, open surfaces ≈ 0, creases occluded, weak occlusion not scaled by one factor, the 2×2 smoothing (diagonal pixels of quads facing the camera equal), the same occlusion in every direction, far samples read from mip levels 1–3 and near ones from level 0 |
//! | `blur` | `sao_blur.frag` | the project's `Res/sao_blur.frag` on the same input (160×112): RMSE, edges kept (one 0.5 m deep), flat surfaces smoothed, mean kept, the impulse response's footprint and symmetry, taps past the border clamped |
//!
//! SAO is graded in five sub-steps, one per lesson that writes `sao.frag` (`steps/sao_parts`,
//! `points::SAO_PARTS`): the view position and normal (6), sampling and mip levels (7), the
//! occlusion term (8), the 2×2 smoothing (9) and the SAO view (10), each with its own verdict and
//! points; a mistake that leaves nothing to measure fails the sub-steps after it, saying so, and a
//! shader that keeps an erratum of the course's printed text has it named. `--level course` passes
//! the course's listings with the documented errata fixed; `--level lesson` (the default) also asks
//! for what the pages teach beyond them.
//!
//! Each step is graded on its own, from the project's inputs (a broken restore pass does not fail the
//! SAO step). With `--res DIR`, a step whose file is missing from DIR (or misnamed, a folder, a
//! link out of DIR, unreadable) fails as "not submitted" (`submitted: false` in `--json`): it is
//! never graded on the project's file. Without `--res` the project grades its own files.
//! `--lesson N` grades what lesson step N has written, as far as it has taught it: the files that
//! `opengl3d lesson N` needs (steps 2–3 the restore pass, 4 also down-sampling, 5 also `simple.frag`,
//! 6–10 also SAO, 11–12 all five), none at step 1 (maths only: the restore pass is still the stub).
//! Lessons 6 and 7 write only the start of `sao.frag` and show it through a debug output (the
//! normal's y; the last tap's mip level ÷ 3): there that output is graded against the project's
//! checkpoint (`Res/lesson-checkpoints/N/sao.frag`, `steps/sao_checkpoint`), and the verdict says
//! that the occlusion is graded from lesson 8 on. Lesson 8 completes the occlusion without the 2×2
//! smoothing, which lesson 9 adds: at 8 the smoothing is neither asked for nor explained. A verdict
//! never gives a later lesson's answer. `--step` picks steps by name and grades each in full; it
//! cannot go with `--lesson`.
//!
//! Every target with an x/y distinction is wider than high (the restore and down-sampling passes,
//! SAO, the blur, `simple.frag`), so that swapped or dropped aspect corrections show.
//!
//! Before rendering, the student's program is checked against the lesson's interface
//! (`shader_interface::PROGRAMS`, in `interface`): a uniform without its `layout(location=N)`, of
//! another type, or a sampler on another unit fails with the declaration to write; one left unread
//! fails so too after rendering, unless the output is mostly Inf or NaN (then that is said: a
//! shader writing a constant Inf reads nothing, its inputs dropped by the compiler). Every
//! message is a `grade.verdict.*` key of `locales/*.yml` (`say!`), in English and the chosen language.
//!
//! Every step runs in a child process (`opengl3d grade-step STEP`, hidden) with a time limit, so a
//! shader that never ends, or a driver crash, fails that step and grading goes on. The child has
//! its own process group (the time limit kills all of it), a memory limit, and dies with the
//! grader. The child prints one JSON object on stdout. Both the student's and the project's passes
//! render into R32F targets (the engine's are R8), so an output that is not normalised shows its
//! real size.
//!
//! `--mutation-score` measures the grader itself: `mutate` writes mutants of the project's shaders,
//! `mutation_probe` tells which differ observably, `mutation_score` counts how many of those fail.
//!
//! `--class DIR` grades every folder (or `.zip`) in DIR as one student, `--jobs` of them at once,
//! each exactly as `--res` grades one, and writes results.csv, report.html (with the failing
//! steps' heat maps) and junit.xml into `--out`.
//!
//! Files: `args` (command line, `Step`), `run` (the grader) with `student` (one folder's steps),
//! `child` (one step's process) and `report`; `class` (a whole class) with `class_report` (its CSV,
//! HTML and JUnit) and `unzip` (.zip submissions); `submission` (finding the student's file);
//! `run_step` (the child) with `staging` (the private copy), `rig` (GL context and both sides'
//! passes), `interface` (the program against the lesson's interface), `passes` (running them),
//! `steps/` (one file per step), `say` (messages), `measure` (shared statistics), `tol` (every
//! tolerance, with what it was measured against); `scene` and `picture` (the SAO scenes and the
//! PNGs, with the colour scale of `crate::io::scale_bar`).

mod args;
mod child;
mod class;
mod class_report;
pub mod classroom50;
pub mod feedback;
mod interface;
mod interrupt;
mod measure;
mod mutate;
mod mutation_probe;
mod mutation_score;
mod passes;
pub mod picture;
pub mod points;
mod report;
mod rig;
mod run;
mod run_step;
mod say;
pub mod scene;
mod staging;
mod steps;
mod student;
mod submission;
mod tol;
mod unzip;

pub use args::{selected_steps, GradeArgs, GradeFormat, GradeStepArgs, Step};
/// How the other tools that run students' shaders start them (`grade --challenge`): confined as
/// the steps are, killed past a time limit, forgotten once reaped.
#[cfg(feature = "bench")]
pub(crate) use child::{spawn_confined, wait_or_kill};
#[cfg(feature = "bench")]
pub(crate) use interrupt::unregister_group;
pub use report::StepReport;
pub use run::run;
pub use run_step::run_step;
