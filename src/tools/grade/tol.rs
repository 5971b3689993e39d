//! The grader's tolerances, in one place. Each was set by running the lesson's listings (errata
//! fixed), correct rewrites and typical mistakes (tests/mutants/) through the grader on Mesa
//! llvmpipe; the comments give what those measured ("listing" is the lesson's code as printed), so
//! that a value can be judged against the margin it leaves on both sides.

/// Restore: allowed error in units of the float-precision bound ε·(1 + B / |D' − B|) (the
/// conditioning of A / (D' − B) in f32). Worst seen: project 0.14×, listing 0.14×, rewrite
/// n·f / (f − D(f − n)) 0.24× of this; mistakes ≥ 10⁵×.
pub const RESTORE_ULPS: f64 = 8.0;
/// Down-sampling: relative error allowed (a min is exact; this only forgives a conversion).
pub const DOWN_REL: f64 = 1e-6;
/// Naming a mistake: a texel matches a mistake's predicted output within this relative error (plus
/// 1e-6 absolute). Loose on purpose: the prediction is computed in f64, the shader works in f32, and
/// the mistakes it tells apart differ by far more (a factor of 2, a sign, a power of ten).
pub const MISTAKE_MATCH_REL: f64 = 1e-3;
/// Naming a mistake: at least this fraction of the texels must match its prediction. Below 1 so that
/// a few texels where two mistakes coincide, or float rounding flips a min, do not hide the match.
pub const MISTAKE_MATCH_FRACTION: f64 = 0.9;
/// SAO: an open, flat surface may show at most the reference's occlusion (itself at most this)
/// plus this. Listing: 0.004 on the open floor (reference 0); a zero bias gives 0.33.
pub const SAO_OPEN_ABS: f64 = 0.05;
/// SAO: a crease must reach at least this fraction of the reference's occlusion (reference
/// 0.71–0.84; listing ≥ 0.73, rewrite ≥ 0.63; flipped normal ≤ 0.10, no max(…, 0) 0.15–0.33)...
pub const SAO_CREASE_FRACTION: f64 = 0.5;
/// ...and at least this much.
pub const SAO_CREASE_MIN: f64 = 0.08;
/// SAO: mean occlusion over pixels facing the camera, away from depth edges, relative to the
/// reference (listing +11%, rewrite +11%, f·f falloff +37%, no max(…, 0) −91%).
pub const SAO_MEAN_REL: f64 = 0.25;
/// SAO: mean occlusion of the band beside a step, relative to the reference (listing +3%,
/// rewrite −1%, f·f falloff +36%, output written in the loop +81%).
pub const SAO_FALLOFF_REL: f64 = 0.2;
/// SAO: mean occlusion of the wall between a raised panel and a post 1.5 m in front of the wall, in
/// the disc (`sao_reach`), relative to the reference (listing +3%, rewrite −1%; the falloff
/// bounded at −1 instead of 0, `max(RADIUS2 − vv, -1)`, −60%).
pub const SAO_NEAR_POST_REL: f64 = 0.2;
/// SAO: RMSE of 8×8 block means against the reference, same pixels as the mean (listing 0.021,
/// rewrite 0.018, f·f 0.029, no max(…, 0) 0.102, flipped normal 0.20).
pub const SAO_BLOCK_RMSE: f64 = 0.035;
/// SAO: where the reference's occlusion (an 8×8 block mean of pixels facing the camera) lies between
/// this and 0.5 / N, the student's ÷ the reference's tells a scaling mistake (below it the ratio is
/// noise; above, a sum N times too strong would be clamped at 1).
pub const SAO_SCALE_FLOOR: f64 = 0.004;
/// SAO: the occlusion is too strong by one factor when the median of those ratios is at least this
/// (listing 1.14, rewrite 1.12, the step-8 shader 1.00; no division by N 10.6; f·f falloff 2.23,
/// which the falloff probe names instead; output written in the loop 2.28).
pub const SAO_SCALE_MIN: f64 = 4.0;
/// SAO: a raw output above this (on more than `SAO_BAD_PIXEL_FRACTION` of the pixels) is not
/// normalised (output written in the loop: 4.5% of the pixels, up to 14.3).
pub const SAO_RAW_MAX: f64 = 1.05;
/// SAO: the fraction of the non-sky pixels that may be NaN, or above `SAO_RAW_MAX`, before the
/// output counts as broken: a few pixels where a degenerate normal slips through are forgiven, a
/// systematic mistake (4.5% above 1 for the output written in the loop) is not.
pub const SAO_BAD_PIXEL_FRACTION: f64 = 0.01;
/// SAO: emptying mip levels 1–3 must move the student's output by at least this fraction of
/// what it moves the project's (listing 1.41, rewrite 1.45; every sample from level 0: 0)...
pub const SAO_MIP_USE: f64 = 0.25;
/// ...and at most this (near samples reading levels 1–3 too: mip level inverted 5.0, level 0
/// never read 12.6)...
pub const SAO_MIP_USE_MAX: f64 = 2.5;
/// ...when the project's own output moves by more than this (mean |Δ| per non-sky pixel; it
/// moves by 0.0034 on the three scenes); otherwise the scenes do not exercise the mips and the
/// check is skipped.
pub const SAO_MIP_CHANGE_MIN: f64 = 0.001;
/// SAO: two diagonal pixels of a 2×2 quad that the lesson's smoothing evens out count as equal
/// within this (float rounding of the two steps leaves about 1e-7; one step of the engine's 8-bit
/// target is 0.004).
pub const SAO_QUAD_SPREAD: f64 = 1e-3;
/// SAO: the fraction of such quads that may be uneven: the project, both listings and the rewrite
/// leave none; without the smoothing (the step-8 shader too), or with its sign wrong, 15% are (the
/// rest are open, all 0).
/// A few quads where the two rows took different branches are forgiven.
pub const SAO_UNEVEN_QUADS: f64 = 0.05;
/// SAO: beside a square panel raised from a wall (seen head-on), the four sides' occlusion may
/// spread by this fraction of its mean (project 0.072, listing 0.077, rewrite 0.067; the disc left
/// stretched, without `aspectFix`, 0.21; `ndcToView.yx` 1.08).
pub const SAO_ANISOTROPY: f64 = 0.15;
/// SAO at `--level lesson`: how much darker than the reference the pixels of quads straddling a
/// silhouette may be on average (the lesson's `onEdge` guard leaves them open: reference 0; no
/// guard 0.398, the listing 0.435; no texel-centre snap 0.023).
pub const SAO_EDGE_DARKER: f64 = 0.1;
/// SAO at `--level lesson`: how much darker than the reference the band within 2 texels of a depth
/// edge may be on average (taps rebuilt off their texel's centre darken it: no snap 0.233 against
/// 0.119; no edge guard 0.127).
pub const SAO_EDGE_BAND: f64 = 0.05;
/// SAO: when every open probe is occluded above this, the bias has the wrong sign (`vn + BIAS`: 1.00
/// on every open probe; no division by the sample count 0.04 at most).
pub const SAO_OPEN_ALL_DARK: f64 = 0.5;
/// SAO at `--level lesson`: how much occlusion the open floor seen from 0.4 m above may show beyond
/// the reference's, far away (texel-centre snap) and near (mip bias).
/// Reference 0 in both bands; no mip bias 0.015 near; no snap and no edge guard together 0.44 far.
pub const SAO_LOW_FLOOR: f64 = 0.01;
/// SAO at `--level lesson`: the fraction of telling 2×2 quads whose smoothing may differ from the
/// reference's (evened out across a depth step, left apart, or halved).
/// Reference 0; the listing 0.016 smeared; no 2 cm test 0.47 and the tests swapped 0.42 smeared;
/// both derivatives first 0.49 halved; the sign flipped 0.81 left apart.
pub const SAO_PATTERN_FRACTION: f64 = 0.05;
/// SAO at `--level lesson`: the fraction of occluded quads whose distance changes by 1.2–1.8 cm per
/// texel along an axis (the lesson's 2 cm test evens them out) that may be left apart. Reference and
/// rewrites with another hash 0; the test at 1 cm 0.31.
pub const SAO_THRESHOLD_BELOW: f64 = 0.1;
/// ...and of those changing by 2.4–3.6 cm that the reference leaves apart, the fraction that may be
/// evened out: another hash or spiral 0.03–0.06 (pairs equal by chance, both 0 or both 1); the
/// clamp to 1 after the smoothing 0.10; the test at 4 cm 0.82.
pub const SAO_THRESHOLD_ABOVE: f64 = 0.3;
/// SAO at `--level lesson`: on the wall beside 3 cm squares, a disc 1.4 texels wide and the
/// occlusion saturated, the mean |student − reference| over the quads touching a square along one
/// axis (the reference leaves the pair's plain mean, 0.5). Another hash 0.023, the spiral's ratios
/// shifted 0.010; the half-texel weights 0.5 as 0.25 along x 0.11, along y 0.097; `min(2.0, …)`
/// before the smoothing 0.21.
pub const SAO_BESIDE_SQUARES_ABS: f64 = 0.06;
/// SAO at `--level lesson`: how much weaker than the reference the occlusion of creases on sloped
/// floors may be, relative (the floor with rows of low blocks at three times the intensity, and the
/// creases of a floor seen from 0.5 m). Another hash or spiral −2 %…+2 %, one tap fewer −4 %; a mip
/// bias on level 0 −25 %…−43 %; the edge test at 5 % of the depth −11 %; `max(sampleDepth, …)` as
/// `min` −53 % on the low floor.
pub const SAO_SLOPED_REL: f64 = 0.1;
/// SAO at `--level lesson`: how much darker than the reference the band within 6 texels of the
/// border may be on a convex box corner whose faces recede towards the left and bottom borders.
/// Reference 0.012 (the mip bias leaves a little), another hash −0.001, the spiral's ratios shifted
/// −0.001; `uv` clamped to −1…1 instead of 0…1 +0.032.
pub const SAO_BORDER_DARKER: f64 = 0.015;
/// SAO at `--level lesson`: with a 5 cm radius (a disc 1.4 texels wide), how far the mean occlusion
/// of the wall's texels beside 3 cm squares may be from the reference's, relative: it counts the taps
/// that cross into a square and what each adds at that distance. Another hash −3 %…+0 %, the spiral
/// turned 4π instead of 2π −3.6 %, reversed +0.3 %, the taps a quarter spacing nearer −3.8 %; a tap
/// more (`i <= N`) +10 %, the taps one spacing nearer (`i − 0.5`) −11 %; the divisor's ε doubled or
/// halved, (vv + 0.002) or (vv + 0.0005), −28 % and +23 %.
pub const SAO_SMALL_DISC_REL: f64 = 0.07;
/// SAO at `--level lesson`: with the lesson's radius, how far the mean occlusion of the wall's
/// texels beside 3 cm squares may be from the reference's, relative: there the first taps, which lie
/// nearest, give most of it. Another hash −0.1 %…+1.9 %, the spiral through 4π +0.5 %, reversed
/// −1.4 %, the loop from 1 to N with (i − 0.5) / N −0.1 %, the taps at (i + 1) / N or (i + 0.25) / N
/// +4 % and +5 %; the first tap dropped (the loop from 1) −47 %, one more at −0.5 / N (from −1) +24 %.
pub const SAO_FIRST_TAPS_REL: f64 = 0.15;
/// SAO: a quad counts as occluded (its unsmoothed pixels differ) above this mean occlusion.
pub const SAO_QUAD_OCCLUDED: f64 = 0.02;
/// SAO: a pair counts as left apart when its pixels differ by this many times `SAO_QUAD_SPREAD`.
pub const SAO_QUAD_APART: f64 = 4.0;
/// SAO: with the intensity raised a hundredfold, the median output where the project's is 1 must
/// reach this (the course clamps with min(1.0, …), so fully occluded is 1): the listings give 1.00;
/// an output clamped to 0.5 gives 0.50.
pub const SAO_SATURATED_MEDIAN: f64 = 0.9;
/// Blur: the mean of a blurred flat noisy surface may move this much (listing 0.0000, no
/// division by totalWeight 0.49 → 5.70).
pub const BLUR_MEAN_ABS: f64 = 0.03;
/// Blur: in the response to a single occluded texel, a value counts as "no tap" below this fraction
/// of the response's peak, and mirror images must agree within it. Float rounding leaves about 1e-6
/// of the peak; the weakest tap is 17% of the peak with the port's weights and 12% with the lesson's
/// (its centre weight is the smallest), so a missing or extra tap is far above it.
pub const BLUR_IMPULSE_REL: f32 = 0.01;
/// Blur: at a depth edge the near side must stay above 1 − this and the far side below this
/// (listing 1.00 | 0.00; no edge weight 0.52 | 0.48; measured with the far side 10 m away, the
/// panel's far side is now 0.5 m behind, which the lesson's weight cuts just as fully).
pub const BLUR_EDGE_ABS: f64 = 0.05;
/// Blur: the weight taps across a depth step of 0.05 m and 0.10 m may have, off the lesson's
/// max(0, 1 − δ / 0.15) (2/3 and 1/3). The listings and the rewrite give it to float precision;
/// `edgeDistance` doubled or halved is off by 0.17 or more, `edgeSharpness = 2 / edgeDistance` by
/// 0.33.
pub const BLUR_EDGE_WEIGHT_ABS: f64 = 0.05;
/// Blur: the noise left on a flat surface, as a fraction of the input's standard deviation
/// (input 0.290; reference 0.038, listing 0.036).
pub const BLUR_SMOOTHING: f64 = 0.6;
/// Blur: how far a sky texel may move from its input. The panel's sky holds noise (input standard
/// deviation 0.29) and sky texels must be returned unchanged, so anything above about five steps of
/// the engine's 8-bit target is a sky texel blurred (no sky test, or `>` instead of `>=`: 0.4 and
/// more).
pub const BLUR_SKY_ABS: f64 = 0.02;
/// Blur: within the blur's reach of the texture's border, where only the outermost texels are
/// occluded, the output may differ by this much from the shader's own output beside an occluded
/// band 9 texels wide inside the texture, which is what clamped reads see (listing and rewrite:
/// 0.000; reads left unclamped 0.48; clamped to `textureSize(…).yx - 1` 0.52).
pub const BLUR_BORDER_ABS: f64 = 0.05;
/// Blur: RMSE on a real SAO buffer against the closer of the project's blur and the same with the
/// course's table (project's file, listing and rewrite 0.000 against one of them, 0.032 against the
/// other, to float precision; no edge weight 0.057, no normalisation 0.110, the edge distance doubled
/// 0.029, the centre weighed g(1)² instead of g(0)² 0.006). On the real buffer and on white noise.
pub const BLUR_RMSE: f64 = 0.004;
/// sao.frag at lesson 6: the normal's y may differ from the checkpoint's by this much at a pixel...
pub const CHECKPOINT_NORMAL_ABS: f64 = 0.02;
/// ...and at lesson 7 the last tap's level ÷ 3 by this (levels are 1/3 apart: any other level is a
/// difference of 0.33 or more).
pub const CHECKPOINT_LEVEL_ABS: f64 = 0.01;
/// Lessons 6 and 7: the fraction of the pixels (of the three SAO scenes) that may differ by more.
/// The listings and the rewrite: 0; the normal flipped 0.38 (walls facing the camera have y = 0
/// either way), `logMipOffset = 4` 0.84, the other lesson's debug view 0.88.
pub const CHECKPOINT_BAD_FRACTION: f64 = 0.01;
/// simple.frag: the largest difference allowed in any channel of the copy and of the composite,
/// against the project's `simple.frag` on the same inputs. The listing and the rewrite
/// (`textureLod`, channels rebuilt from `.rgb` and `.a`) run the same sampler and give exactly 0;
/// the mistakes differ by whole channels: red broadcast 0.98, alpha 1 0.76, `.bgra` 0.98, upside
/// down 0.76, nearest texels on the 2× magnification 0.39.
pub const SIMPLE_ABS: f64 = 1e-3;
/// A program that leaves an input unread fails with the output's Inf or NaN instead when more than
/// this fraction of what it writes is Inf or NaN: a shader writing a constant Inf writes it
/// everywhere (1.0) and reads nothing, the compiler having dropped every input; a shader that only
/// misses one uniform writes finite values (0.0).
pub const NONFINITE_OVER_UNREAD: f64 = 0.5;
/// Mutation testing: a mutant is equivalent to the shader it was made from when every value of
/// every probe render differs from that shader's by at most this, relative to the value (or to 1,
/// the scale of occlusion, for values below 1). f32 carries 24 bits (ε = 1.2e-7): 1e-6 is 8 units
/// in the last place, the rounding a few reordered operations leave. On the project's shaders the
/// equivalent mutants differ by at most 0.54e-6 (the blur's symmetric taps summed in mirrored
/// order), every other one by at least 7e-4 (a sign in the restore's depth constants).
pub const EQUIVALENT_REL: f64 = 1e-6;
