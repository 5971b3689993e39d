//! What a frame shows.

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum View {
    /// The lit scene with AO blended in.
    #[default]
    Composite,
    /// The half-size linear depth buffer (metres).
    LinearDepth,
    /// The second depth layer at the same size (metres, `far` where nothing is hidden): `vbao`
    /// with `layers = 2` only.
    SecondLayerDepth,
    /// The SAO buffer before the blur, as visibility (1 = open).
    AoRaw,
    /// The blurred SAO buffer, as visibility.
    Ao,
}

impl View {
    pub const ALL: [View; 5] = [
        View::Composite,
        View::LinearDepth,
        View::SecondLayerDepth,
        View::AoRaw,
        View::Ao,
    ];
    /// The next view in `ALL`, skipping the second layer's unless `second_layer` (the settings
    /// draw one).
    pub fn next(self, second_layer: bool) -> View {
        let i = View::ALL.iter().position(|v| *v == self).unwrap_or(0);
        let next = View::ALL[(i + 1) % View::ALL.len()];
        if next.available(second_layer) {
            next
        } else {
            next.next(second_layer)
        }
    }
    /// Whether the view can be drawn: the second layer's only when the settings draw one.
    pub fn available(self, second_layer: bool) -> bool {
        second_layer || self != View::SecondLayerDepth
    }
    /// A view of linear depth (no AO method runs).
    pub fn is_depth(self) -> bool {
        matches!(self, View::LinearDepth | View::SecondLayerDepth)
    }
    pub fn label(self) -> &'static str {
        match self {
            View::Composite => "composite",
            View::LinearDepth => "linear depth",
            View::SecondLayerDepth => "second layer depth",
            View::AoRaw => "raw SAO",
            View::Ao => "blurred SAO",
        }
    }
    /// The command line's name (`--view`).
    pub fn name(self) -> &'static str {
        match self {
            View::Composite => "composite",
            View::LinearDepth => "linear-depth",
            View::SecondLayerDepth => "linear-depth-2",
            View::AoRaw => "ao-raw",
            View::Ao => "ao",
        }
    }
    pub fn from_name(name: &str) -> Option<View> {
        View::ALL.into_iter().find(|v| v.name() == name)
    }
}
