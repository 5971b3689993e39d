//! What a frame shows.

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum View {
    /// The lit scene with AO blended in.
    #[default]
    Composite,
    /// The half-size linear depth buffer (metres).
    LinearDepth,
    /// The SAO buffer before the blur, as visibility (1 = open).
    AoRaw,
    /// The blurred SAO buffer, as visibility.
    Ao,
}

impl View {
    pub const ALL: [View; 4] = [View::Composite, View::LinearDepth, View::AoRaw, View::Ao];
    pub fn next(self) -> View {
        let i = View::ALL.iter().position(|v| *v == self).unwrap_or(0);
        View::ALL[(i + 1) % View::ALL.len()]
    }
    pub fn label(self) -> &'static str {
        match self {
            View::Composite => "composite",
            View::LinearDepth => "linear depth",
            View::AoRaw => "raw SAO",
            View::Ao => "blurred SAO",
        }
    }
    /// The command line's name (`--view`).
    pub fn name(self) -> &'static str {
        match self {
            View::Composite => "composite",
            View::LinearDepth => "linear-depth",
            View::AoRaw => "ao-raw",
            View::Ao => "ao",
        }
    }
    pub fn from_name(name: &str) -> Option<View> {
        View::ALL.into_iter().find(|v| v.name() == name)
    }
}
