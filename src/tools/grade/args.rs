//! The grader's command line: which steps to grade (`opengl3d grade`), and the hidden child command
//! that grades one of them (`opengl3d grade-step`).

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// How strict the grader is (`--level`): `course` passes the original listings with the documented
/// errata fixed; `lesson` also asks for what the pages add (the depth-edge guard, the mip bias,
/// the texel-centre snap, the smoothing's 2 cm tests, derivatives outside branches).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    Course,
    #[default]
    Lesson,
}

impl Level {
    pub fn name(self) -> &'static str {
        match self {
            Level::Course => "course",
            Level::Lesson => "lesson",
        }
    }
}

#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, ValueEnum)]
pub enum Step {
    Restore,
    DownSampling,
    Simple,
    Sao,
    Blur,
}

impl Step {
    /// In the order the lesson has them written.
    pub const ALL: [Step; 5] = [
        Step::Restore,
        Step::DownSampling,
        Step::Simple,
        Step::Sao,
        Step::Blur,
    ];

    /// The shader file the step grades.
    pub fn file(self) -> &'static str {
        match self {
            Step::Restore => "sao_restore_depth.frag",
            Step::DownSampling => "sao_down_sampling.frag",
            Step::Simple => "simple.frag",
            Step::Sao => "sao.frag",
            Step::Blur => "sao_blur.frag",
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Step::Restore => "restore",
            Step::DownSampling => "down-sampling",
            Step::Simple => "simple",
            Step::Sao => "sao",
            Step::Blur => "blur",
        }
    }
    fn from_file(file: &str) -> Option<Step> {
        Step::ALL.into_iter().find(|s| s.file() == file)
    }
}

/// `grade --format`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum GradeFormat {
    Text,
    Json,
    Classroom50,
}

#[derive(Args, Debug, Clone)]
pub struct GradeArgs {
    /// Grade the shaders lesson step N has written, as far as it has taught them (1: none yet;
    /// 2-3: restore; 4: and down-sampling; 5: and simple; 6-10: and SAO, 6-7 grading the step's
    /// debug output, 8 the occlusion without the 2x2 smoothing of 9; 11-12: all five).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub lesson: Option<u32>,
    /// Grade only these steps (comma-separated or repeated), each in full; not with --lesson.
    #[arg(long, value_enum, value_delimiter = ',', conflicts_with = "lesson")]
    pub step: Vec<Step>,
    /// Print the verdicts as JSON: {"passed": bool, "steps": [{"step", "file", "passed", "submitted",
    /// "message"}]}; the keys and "message" stay English, and a message also written in Japanese
    /// (`--lang ja`, or a ja locale) comes as "message_localised" too.
    #[arg(long)]
    pub json: bool,
    /// How the verdicts are written: `text` (the default), `json` (as --json), or `classroom50`:
    /// the text, and result.json in the working directory as a Classroom 50 autograder must leave
    /// it (one test per graded step with its points, identity from the runner's CLASSROOM,
    /// ASSIGNMENT, SUBMISSION_TAG, COMMIT_URL, RELEASE_URL and REVIEW_URL), the heat maps and
    /// feedback.html in --out (default: grade-report); exits 0 once result.json is written.
    #[arg(long, value_enum, conflicts_with_all = ["json", "class", "mutation_score"])]
    pub format: Option<GradeFormat>,
    /// Folder for expected/actual/difference PNGs of each step; with --class, the folder for the
    /// class's report (results.csv, report.html, junit.xml; default: grade-report).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Grade a whole class: each folder in DIR is one student's shaders (named after the folder).
    #[arg(long, value_name = "DIR", conflicts_with = "json")]
    pub class: Option<PathBuf>,
    /// With --class, how many students are graded at once; with --mutation-score, how many mutants
    /// (default: the number of cores).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub jobs: Option<usize>,
    /// Measure the grader: grade every mutant of the project's lesson shaders (of --step, or all
    /// five) and print per step the fraction of the faults (mutants whose output differs from the
    /// shader's) it fails; exit 1 when it passes a fault beyond the step's tolerance.
    #[arg(long, conflicts_with_all = ["class", "lesson", "out"])]
    pub mutation_score: bool,
    /// With --mutation-score, only N mutants per step, evenly spread (a quick sample).
    #[arg(
        long,
        value_name = "N",
        requires = "mutation_score",
        allow_negative_numbers = true
    )]
    pub mutation_sample: Option<usize>,
    /// Give each step points (earned when it passes), shown in --json and in --class's results.csv
    /// and junit.xml: `STEP=N` pairs (`sao=40,blur=20`; steps not named keep their default), or
    /// alone the default, 10 per lesson step that writes the file: restore 20, down-sampling 10,
    /// simple 10, sao 50, blur 10.
    #[arg(
        long,
        value_name = "STEP=N,...",
        num_args = 0..=1,
        default_missing_value = "default",
        conflicts_with = "mutation_score"
    )]
    pub points: Option<String>,
    /// Seconds each step may take before it counts as hung (an endless loop in a shader).
    #[arg(
        long,
        default_value_t = 20.0,
        value_name = "SECONDS",
        allow_negative_numbers = true
    )]
    pub timeout: f64,
    /// Also print each step's measurements on stderr.
    #[arg(long)]
    pub verbose: bool,
    /// How strict: `course` (the original listings with the documented errata fixed pass) or
    /// `lesson` (also what the pages teach beyond them); shown in every report.
    #[arg(long, value_enum, default_value_t = Level::Lesson)]
    pub level: Level,
    /// A class challenge: rank the method files in DIR (and in its folders, one per student) by
    /// their error against the ray-traced truth on the scenes' test cameras, among those whose AO
    /// chain costs at most --budget times the lesson chain's; writes report.html to --out (default
    /// challenge-report). See docs/grade/challenge.md.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["class", "mutation_score", "json", "format", "lesson", "step", "points"])]
    pub challenge: Option<PathBuf>,
    /// With --challenge: the most an entry's AO chain may cost, as a multiple of the lesson chain's.
    #[arg(
        long,
        default_value_t = 1.0,
        requires = "challenge",
        allow_negative_numbers = true
    )]
    pub budget: f64,
    /// With --challenge: the scenes (default: the demo scene); scenes of your own keep the cameras
    /// unknown to the class.
    #[arg(long, value_name = "FILE", requires = "challenge")]
    pub scene: Vec<PathBuf>,
    /// With --challenge: seconds each entry may take, all its scenes together.
    #[arg(
        long,
        default_value_t = 600.0,
        value_name = "SECONDS",
        requires = "challenge",
        allow_negative_numbers = true
    )]
    pub entry_timeout: f64,
}

/// The hidden child command: grades one step and prints its report as JSON.
#[derive(Args, Debug, Clone)]
pub struct GradeStepArgs {
    #[arg(value_enum)]
    pub step: Step,
    /// Private working folder (the graded file is copied there).
    #[arg(long)]
    pub work: PathBuf,
    /// Folder for the step's PNGs.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The lesson step the student is at (`grade --lesson N`): a file the lesson has only begun
    /// (`sao.frag` at steps 6–7) is checked as far as it is written.
    #[arg(long)]
    pub lesson: Option<u32>,
    /// Also render the mutation-testing probe and add its difference from the project's output to
    /// the report's metrics (`grade --mutation-score`).
    #[arg(long)]
    pub probe: bool,
    /// How strict (`grade --level`).
    #[arg(long, value_enum, default_value_t = Level::Lesson)]
    pub level: Level,
}

/// The lesson step the children are told about: `--lesson N` (`--step`, which cannot come with it,
/// grades each step in full).
pub fn lesson_of(args: &GradeArgs) -> Option<u32> {
    args.lesson
}

/// The steps `args` select, in the lesson's order.
pub fn selected_steps(args: &GradeArgs) -> Result<Vec<Step>> {
    let mut steps: Vec<Step> = if !args.step.is_empty() {
        args.step.clone()
    } else if let Some(n) = args.lesson {
        if !(1..=crate::tools::lesson::STEPS).contains(&n) {
            let steps = crate::tools::lesson::STEPS;
            bail!(
                "{}",
                rust_i18n::t!("lesson.no_such_step", n = n, steps = steps)
            );
        }
        // Step 1 shows the stub it starts from: the restore pass is written from step 2 on.
        if n < crate::tools::lesson::FIRST_SHADER_STEP {
            return Ok(Vec::new());
        }
        crate::tools::lesson::shaders_for_step(n)
            .iter()
            .filter_map(|f| Step::from_file(f))
            .collect()
    } else {
        Step::ALL.to_vec()
    };
    steps.sort();
    steps.dedup();
    Ok(steps)
}
