#version 450
#extension GL_GOOGLE_include_directive : require
#pragma sao effect sao version=1

// Scalable Ambient Obscurance (McGuire, Mara, Luebke, HPG 2012) as annotated compute shaders.
// The format of the `#pragma sao` lines: docs/effect-format.md. Every formula, its order of
// operations and how host code fills the parameter block: docs/effect-math.md.
//
// Passes: linear_z (eq. 2 and the z MIP chain, Table 1's rotated grid) -> ao_sample (eq. 3-10 + 2x2
// reconstruction) -> blur (the separable bilateral blur, both directions in one dispatch) ->
// output (full resolution: A into the output's format) or, with resolution_divisor d > 1, upsample
// (ao_sample and the blur ran on the viewport over d, rounded up; reduced pixel p covers viewport
// pixels [p*d, p*d + d)). Without blur (blur_radius 0) output or upsample reads ao_raw.
// Camera space is right-handed, the camera looks down -z, so geometry has z < 0; +0.0 in csz marks
// sky / no geometry.

// ---------------------------------------------------------------------------------------------
// Settings (host side; the shaders only see block members computed from them). The appearance
// defaults (bias, contrast; intensity 1, epsilon 1e-4) are calibrated against ray-traced near-field AO
// at radius 1 m over the built-in scenes (`sao-bench --sections calibrate`, docs/BENCHMARKS.md).
// ---------------------------------------------------------------------------------------------
#pragma sao setting float radius              default=1.0   range=[0.01,100]       unit=m   "World-space radius r of the obscurance ball (eq. 1, 5)"
#pragma sao setting float bias                default=0.01  range=[0,0.5]                   "Bias beta of eq. 1: the term v.n + z_C*beta, a unitless multiplier of |z_C|; raise to remove self-occlusion, lower if corners leak light"
#pragma sao setting float intensity           default=1.0   range=[0,10]                    "Intensity sigma of eq. 1, unitless: the sum is scaled by 2*sigma*r/s with r the radius, so A does not change with the scene's units"
#pragma sao setting float contrast            default=1.25  range=[0.1,8]                   "Contrast exponent k of eq. 1"
#pragma sao setting float epsilon             default=0.0001 range=[0.000001,0.01] unit=m^2 "Epsilon of eq. 1 added to v.v against division by zero"
#pragma sao setting int   samples             default=48    range=[1,64]                    "Direct samples s per pixel (spiral taps)"
#pragma sao setting int   spiral_turns        default=0     range=[0,64]                    "Turns tau of the tap spiral (eq. 6); 0: the built-in choice for the sample count (docs/effect-math.md 2.4)"
#pragma sao setting int   mip_switch_log2     default=4     range=[0,5]            unit=px  "log2 of q', the tap distance in pixels at which taps move to the next coarser z MIP level (eq. 9)"
#pragma sao setting bool  use_z_hierarchy     default=true                                  "Read taps from the z MIP hierarchy (false: always level 0, the no-MIP baseline)"
#pragma sao setting int   blur_radius         default=1     range=[0,8]                     "Bilateral blur taps on each side of the centre (0: no blur)"
#pragma sao setting int   blur_stride         default=1     range=[1,4]            unit=px  "Pixels between bilateral blur taps"
#pragma sao setting float blur_edge_sharpness default=10.0  range=[0,1000]         unit=1/m "Bilateral blur depth weight max(0, 1 - (sharpness + blur_edge_relative/|z|)*|dz|): with blur_edge_relative 0, taps 1/sharpness apart in z get weight 0"
#pragma sao setting bool  blur_edge_slope     default=true                                  "Bilateral blur: a tap's z is compared with the centre's plane along the blur direction (the flatter of the centre's two one-sided slopes to its neighbours blur_stride away; none at a ridge or a valley) instead of with the centre's z, so that a slanted floor blurs as a flat one does while a step still cuts"
#pragma sao setting float blur_edge_relative  default=0.0   range=[0,10000]                 "Bilateral blur depth weight, the part relative to the centre's distance: taps |dz|/|z| = 1/blur_edge_relative apart get weight 0 (with blur_edge_sharpness 0). Scale-free: a scene in millimetres blurs as the same scene in metres; blur_edge_sharpness's 1/m does not"
#pragma sao setting float quad_edge_threshold default=0.02  range=[0,10]           unit=m   "2x2 reconstruction: quad neighbours average only when their z differ by less than this"
#pragma sao setting int   resolution_divisor  default=2     values=[1,2,4]                  "AO resolution per axis: 1 full, 2 half, 4 quarter. ao_sample, the 2x2 reconstruction and the blurs run at the viewport over it (rounded up) and a depth-aware upsample writes the full-resolution output"
#pragma sao setting float fade_start          default=0.0   range=[0,100000]       unit=m   "Distance fade: camera distance -z where the AO starts to fade towards 1 (unoccluded); used only when fade_end > 0, and must then be below fade_end"
#pragma sao setting bool  temporal            default=false                                 "Accumulate frames (TEMPORAL): each pixel's obscurance sum is blended with the previous frames' of the same surface, reprojected through the previous and this frame's camera (Camera::view) and rejected by depth; count Inputs::frameIndex up so that frames sample different taps"
#pragma sao setting float temporal_hysteresis default=0.9   range=[0,0.99]                  "Temporal: the history's largest share of a pixel once it holds 1/(1 - h) frames (a running mean up to then, an exponential one after); 0 = this frame only"
#pragma sao setting float temporal_depth_tolerance default=0.05 range=[0.001,1]             "Temporal: relative z difference |z_history - z| / |z| at which a history texel weighs 0 (linearly down from 1 at 0): the disocclusion test"
#pragma sao setting float fade_end            default=0.0   range=[0,100000]       unit=m   "Distance fade: camera distance -z from which A = 1, linear in distance from fade_start on; 0 = no fade"
#pragma sao setting float albedo              default=0.0   range=[0,1]                     "Multi-bounce: the surface albedo rho of Jimenez et al. 2016's fit max(A, ((a A + b) A + c) A), applied to A where the output is written; 0: single bounce, A unchanged (docs/effect-math.md, Multi-bounce)"
#pragma sao setting bool  half_intermediates  default=true                                  "rg16f (A, key) intermediates (HALF_INTERMEDIATES): ao_raw and ao_low take 4 bytes a texel instead of 8, A and the key z (in about metres) rounded to binary16; false: rg32f (docs/effect-math.md, section 6.5)"
#pragma sao setting int   estimator           default=0     values=[0,1]                    "0 alchemy: the paper's eq. 1, as before; 1 visibility: cosine-weighted visibility with a finite thickness, horizon slices with a visibility bitmask (docs/effect-math.md)"
#pragma sao setting float thickness           default=0.3   range=[0.001,100]      unit=m   "Visibility estimator: the thickness T of every stored surface; a ray is blocked where it passes through the slab from the surface (plus the tolerance) to T behind it"
#pragma sao setting float depth_tolerance     default=0.003 range=[0,0.1]                   "Visibility estimator: relative depth tolerance; the slab behind a stored sample starts at its depth times (1 + tolerance)"
#pragma sao setting int   slices              default=2     range=[1,8]                     "Visibility estimator: slices (screen directions, both sides each) per pixel; samples/(2*slices) steps on each side"
#pragma sao setting int   thickness_model     default=0     values=[0,1]                    "Visibility estimator: 0 constant, every stored surface is thickness deep; 1 width, a surface is as deep as SAO_WIDTH_SCALE times its on-screen width along the slice (its run of continuous depth along x and y, measured by the width pass on each csz level up to SAO_WIDTH_REACH of its texels each side, a run wide on one level measured on the next), from SAO_WIDTH_MIN_M up to thickness: thin objects (grass, rods) stop few rays, wide ones many (docs/effect-math.md 5.9)"
#pragma sao setting bool  bent_normals        default=false                                 "Visibility estimator: also write the bent normal, the cosine-weighted mean direction of the unoccluded rays over the slices (camera space, unit length; the normal where no ray is clear, 0 for sky), into the output's R, G, B (rgba8: 0.5 + 0.5 b) and A into A; needs estimator 1, an rgba8 or rgba16f output, every channel, the replace blend and the direct path (blur_radius 0, resolution_divisor 1, temporal false). The 2x2 reconstruction averages A only: the bent normal is the pixel's own (docs/effect-math.md 5.10)"
// Derived settings: bools plan() computes from the settings, for the passes' skip_when= rules.
#pragma sao derived direct_output when=blur_radius==0&&resolution_divisor==1&&temporal==false "Nothing follows the AO (no blur, full resolution, no history to keep): ao_sample_output writes the output itself, and neither ao_raw nor a copy pass is planned"
#pragma sao derived copy_to_output when=resolution_divisor==1&&direct_output==false "Full resolution, and ao_sample wrote (A, key) (for the blur, or for the temporal history): the pass output copies A into the output"
// Inert settings: a setting whose value reaches no pass that runs while the condition holds (each
// checked against computeConstants and the passes below). Programs refuse such a setting when the
// user gave it (--set), whatever the preset set; sao-viewer greys it out with the reason.
// Not inert in this sense: everything while intensity = 0 (A = 1, but every pass still runs and costs).
#pragma sao inert fade_start               when=fade_end==0              "no distance fade: sao_fade returns A unchanged and fade_start is not uploaded"
#pragma sao inert temporal_hysteresis      when=temporal==false          "no temporal accumulation: there is no history for it to weigh"
#pragma sao inert temporal_depth_tolerance when=temporal==false          "no temporal accumulation: there is no history texel for it to reject"
#pragma sao inert blur_stride              when=blur_radius==0           "no bilateral blur: the blur pass does not run"
#pragma sao inert blur_edge_sharpness      when=blur_radius==0           "no bilateral blur: the blur pass does not run"
#pragma sao inert blur_edge_relative       when=blur_radius==0           "no bilateral blur: the blur pass does not run"
#pragma sao inert blur_edge_slope          when=blur_radius==0           "no bilateral blur: the blur pass does not run"
#pragma sao inert mip_switch_log2          when=use_z_hierarchy==false   "no z MIP hierarchy: every tap reads level 0, there is no level to switch to"
#pragma sao inert half_intermediates       when=direct_output==true      "ao_sample_output writes the output itself: there are no (A, key) intermediate images"
#pragma sao inert bias                     when=estimator==1             "the visibility estimator has no eq. 1 term for a bias to offset"
#pragma sao inert epsilon                  when=estimator==1             "the visibility estimator has no eq. 1 term for an epsilon to guard"
#pragma sao inert spiral_turns             when=estimator==1             "the visibility estimator samples slices, not the spiral"
#pragma sao inert thickness                when=estimator==0             "the alchemy estimator (eq. 1) has no thickness model; thickness is not uploaded"
#pragma sao inert depth_tolerance          when=estimator==0             "the alchemy estimator (eq. 1) has no thickness model; depth_tolerance is not uploaded"
#pragma sao inert slices                   when=estimator==0             "the alchemy estimator (eq. 1) samples the spiral, not slices; slices is not uploaded"
#pragma sao inert thickness_model          when=estimator==0             "the alchemy estimator (eq. 1) has no thickness model; thickness_model is not uploaded"
// Refused settings: a value other than the default that the passes planned under the others cannot
// carry; plan() fails with the rule (sao::checkRefusals), every program too.
#pragma sao refuse bent_normals            when=estimator==0             "the alchemy estimator (eq. 1) has no slices of unoccluded rays to average"
#pragma sao refuse bent_normals            when=direct_output==false     "ao_sample_output alone writes the bent normal: the blur, the upsample and the temporal history carry A only"
// ---------------------------------------------------------------------------------------------
// Presets: the chain `sao-bench --tune --objective a` chose on the Pareto front of time against the
// RMSE vs ray-traced AO (a) over the built-in scenes, blotch and silhouette figures held to their
// limits (docs/BENCHMARKS.md, "The tuner against (a), third run"; 2026-12-05, gl, 640x360, 4096
// rays): time budgets 0.2/0.5/1/2/4 x the untuned medium (11 taps, 7-tap blur, full resolution),
// each step slower and nearer (a) on every scene; every one keeps the z hierarchy (what keeps the
// cost flat in the radius on a GPU). low to high keep the paper's estimator; ultra and reference
// are the visibility estimator with thickness from width up to 1 m. The settings' defaults above
// are the high preset (no visibility point met the default's blotch limit at its time). Unlisted
// settings keep their defaults. Since 2026-12-08 every preset blurs along the slope
// (blur_edge_slope's default: each one nearer (a) on every scene, 640x360) and ultra and reference
// weigh the blur's depth edge relative to z (1/200; the hold-out engine's fins), BENCHMARKS "The
// blur's depth edge along a slope".
// ---------------------------------------------------------------------------------------------
#pragma sao preset low       samples=4 blur_radius=1 blur_stride=1 use_z_hierarchy=true mip_switch_log2=3 resolution_divisor=4 "4 taps, 2x2 + 3-tap blur (stride 1), z hierarchy (q' = 8 px), 1/4 resolution"
#pragma sao preset medium    samples=24 blur_radius=1 blur_stride=1 use_z_hierarchy=true mip_switch_log2=4 resolution_divisor=2 "24 taps, 2x2 + 3-tap blur (stride 1), z hierarchy (q' = 16 px), 1/2 resolution"
#pragma sao preset high      samples=48 blur_radius=1 blur_stride=1 use_z_hierarchy=true mip_switch_log2=4 resolution_divisor=2 "48 taps, 2x2 + 3-tap blur (stride 1), z hierarchy (q' = 16 px), 1/2 resolution: the settings' defaults"
#pragma sao preset ultra     samples=32 blur_radius=2 blur_stride=1 use_z_hierarchy=true mip_switch_log2=4 resolution_divisor=2 blur_edge_sharpness=0 estimator=1 slices=2 thickness=1 thickness_model=1 blur_edge_relative=200 "visibility (2 slices, thickness from width up to 1 m), 32 taps, 2x2 + 5-tap blur (stride 1, edge 1/200 of z), z hierarchy (q' = 16 px), 1/2 resolution"
#pragma sao preset reference samples=32 blur_radius=3 blur_stride=2 use_z_hierarchy=true mip_switch_log2=4 resolution_divisor=1 blur_edge_sharpness=0 estimator=1 slices=2 thickness=1 thickness_model=1 blur_edge_relative=200 "visibility (2 slices, thickness from width up to 1 m), 32 taps, 2x2 + 7-tap blur (stride 2, edge 1/200 of z), z hierarchy (q' = 16 px), full resolution"

// ---------------------------------------------------------------------------------------------
// Constants
// ---------------------------------------------------------------------------------------------
#pragma sao constant int  SAO_MAX_MIP_LEVELS=8 "Most csz MIP levels ever allocated (level 0 and 7 reduced ones); max_mip <= SAO_MAX_MIP_LEVELS-1"
#pragma sao constant int  SAO_MAX_SAMPLES=64 "Upper bound of samples; the tap loop clamps to it"
#pragma sao constant int  SAO_MAX_BLUR_RADIUS=8 "Upper bound of blur_radius; the blur loop clamps to it and the block holds Gaussian weights for taps 1..8"
#pragma sao constant int  SAO_MAX_BLUR_STRIDE=4 "Upper bound of blur_stride (its range's end); the blur's shared tile holds SAO_MAX_BLUR_RADIUS * SAO_MAX_BLUR_STRIDE rows above and below its own"
#pragma sao constant int  SAO_MAX_RADIUS_PX=65536 "Clamp of the projected radius r' in pixels (eq. 5), so that tap offsets never overflow an int"
#pragma sao constant uint SAO_PHASE_MUL=1270342730 "Eq. 8 rotation: 2*SAO_PHASE_MUL/2^32 = frac(10/(2*pi)), turning the hash times 10 radians into 2^-32 turns"
#pragma sao constant int  SAO_DEPTH_MODE_PERSPECTIVE=0 "depth_mode: hardware depth of a perspective projection, z = c0/(d*c1 + c2) (eq. 2)"
#pragma sao constant int  SAO_DEPTH_MODE_ORTHOGRAPHIC=1 "depth_mode: hardware depth of an orthographic projection, z = d*c1 + c2"
#pragma sao constant float SAO_UPSAMPLE_Z_SHARPNESS=32.0 "upsample depth weight max(0, 1 - SHARPNESS*|z - z_low|/|z|): low-resolution texels 1/32 (3.1%) apart in relative z get weight 0 (16, 64 and 256 compared in docs/BENCHMARKS.md, Reduced resolution)"
#pragma sao constant float SAO_TEMPORAL_NORMAL_COS=0.7 "temporal, with supplied normals: a history texel whose normal lies more than acos(0.7) = 45.6 degrees from the pixel's weighs 0 (another surface at the same depth: an edge, a crease)"
#pragma sao constant int  SAO_DEPTH_MODE_LINEAR=2 "depth_mode: the input already holds linear camera-space z (R32F), z = d*c1 + c2 (normally c1 = 1, c2 = 0)"
#pragma sao constant int  SAO_NORMALS_CAMERA_XYZ=0 "normals_encoding: camera-space normal in .xyz (sao::NormalsEncoding::CameraXyz)"
#pragma sao constant int  SAO_NORMALS_WORLD_XYZ=1 "normals_encoding: world-space normal in .xyz, rotated by view_x/y/z (WorldXyz)"
#pragma sao constant int  SAO_NORMALS_CAMERA_OCTAHEDRAL=2 "normals_encoding: camera-space normal, signed octahedral map in .xy (CameraOctahedral)"
#pragma sao constant int  SAO_NORMALS_WORLD_OCTAHEDRAL=3 "normals_encoding: world-space normal, signed octahedral map in .xy, rotated by view_x/y/z (WorldOctahedral)"
#pragma sao constant int  SAO_OUTPUT_BLEND_REPLACE=0 "output_blend: the output's selected channels receive A (sao::OutputBlend::Replace)"
#pragma sao constant int  SAO_DEPTH_SAMPLE_0=0 "depth_sample_policy: a multisampled depth input's sample 0 stands for its texel (sao::DepthSamplePolicy::Sample0)"
#pragma sao constant int  SAO_DEPTH_SAMPLE_NEAREST=1 "depth_sample_policy: the sample nearest to the camera (the largest geometry z; sky only when every sample is sky) stands for its texel (Nearest)"
#pragma sao constant int  SAO_MAX_SLICES=8 "Upper bound of slices (its range's end)"
#pragma sao constant int  SAO_WIDTH_REACH=16 "thickness_model 1: texels of its own csz level the width pass walks on each side of a texel along x and along y; a run of continuous depth that goes on through all of them on either side is wide on that level, and takes its share from the level above (width_resolve); wide at every level up to max_mip, it is as deep as thickness"
#pragma sao constant float SAO_WIDTH_SCALE=0.5 "thickness_model 1: a surface's thickness is this times its on-screen width along the slice (reference (d) measured 0.5 best of 0.5, 1, 2: docs/reference.md)"
#pragma sao constant float SAO_WIDTH_JUMP=0.03 "thickness_model 1: neighbouring texels whose z differ by more than this times z per level-0 texel are a depth discontinuity (an edge of the run)"
#pragma sao constant float SAO_WIDTH_MIN_M=0.02 "thickness_model 1: the least thickness, metres (uploaded in view units as thickness_min)"
#pragma sao constant int  SAO_OUTPUT_BLEND_MULTIPLY=1 "output_blend: the output's selected channels are multiplied by A, the apply step of an engine's colour or occlusion target (sao::OutputBlend::Multiply)"
#pragma sao constant int  SAO_BENT_BISECTIONS=16 "Bent normal of the visibility estimator: halvings of a slice's hemisphere [lo, hi] that find the angle of a visible run's end from its slice position (G inverted; pi / 2^16 = 5e-5 rad)"

// ---------------------------------------------------------------------------------------------
// Variants
// ---------------------------------------------------------------------------------------------
#pragma sao variant NORMALS_SUPPLIED values=[0,1] default=0 select=input:normals "0: face normals rebuilt from csz level 0 (eq. 4, explicit neighbour fetches, smaller-|dz| side per axis); 1: read the normals input (e.g. rgba16f), encoded as normals_encoding says (camera or world space, xyz or octahedral .xy)"
#pragma sao variant TWO_LAYER values=[0,1] default=0 select=input:depth2 "1: deep G-buffer, a second depth layer; each tap takes the larger obscurance of the two layers' points"
#pragma sao variant Z_HIERARCHY values=[0,1] default=1 select=use_z_hierarchy "1: taps read z MIP level clamp(findMSB(int(h)) - log_q, 0, max_mip) (eq. 9-10); 0: always level 0 (the AlchemyAO / no-MIP baseline)"
#pragma sao variant OUTPUT_FORMAT values=[0,1,2,3] default=0 select=output:ao "The output image's format, an index into ao's formats=: 0 r16f, 1 r8 (A rounded to the nearest 1/255), 2 rgba8, 3 rgba16f (RGBA: A goes into the channels output_mask selects, the others keep their texels)"
#pragma sao variant DEPTH_MULTISAMPLE values=[0,1] default=0 select=multisampled:depth "1: the depth input is multisampled (sampler2DMS, depth_samples per texel); linear_z keeps one sample per texel as depth_sample_policy says (sample 0, or the nearest to the camera)"
#pragma sao variant TEMPORAL values=[0,1] default=0 select=temporal "1: ao_sample blends each pixel's obscurance sum with the history of the previous frames (sao_temporal.glsl) and writes this frame's history"
#pragma sao variant HALF_INTERMEDIATES values=[0,1] default=0 select=half_intermediates "1: the (A, key) intermediates are rg16f: the passes writing them round A and the key (z times key_scale = 1/metersToViewUnits: z in metres) to binary16 themselves"
#pragma sao variant MOTION_VECTORS values=[0,1] default=0 select=input:motion "1: temporal accumulation finds each pixel's history where the motion input says the surface was (moving objects) instead of reprojecting through the cameras"
#pragma sao variant ESTIMATOR values=[0,1] default=0 select=estimator "0: the AlchemyAO estimator (eq. 1) over the spiral taps; 1: the visibility estimator, cosine-weighted visibility with a finite thickness over slices with a visibility bitmask (sao_visibility.glsl)"
#pragma sao variant THICKNESS_FROM_WIDTH values=[0,1] default=0 select=thickness_model "1: the width and width_resolve passes write csz_share, each csz texel's z beside its shares of thickness from its run of continuous depth along x and y, and the visibility estimator's taps read it instead of csz (one fetch a tap); a variant, not a branch, because llvmpipe runs a branch's body masked on every tap. With ESTIMATOR 0 the AO does not change (thickness_model is inert then), but the width passes still run, writing 1s (thickness is 0): ao_sample's csz_share binding needs a writer"
#pragma sao variant BENT_NORMALS values=[0,1] default=0 select=bent_normals "1: ao_sample_output sums the slices' first moments of their unoccluded rays with the occlusion (sao_bent.glsl) and stores (bent normal, A) into the rgba output"
#pragma sao exclude MOTION_VECTORS=1 TEMPORAL=0 "motion vectors serve temporal accumulation only: set the temporal setting, or give no motion input"
#pragma sao exclude DEPTH_MULTISAMPLE=1 TWO_LAYER=1 "a multisampled depth input has no second layer: give depth peeling's layers single-sample, or resolve the depth first"
#pragma sao exclude Z_HIERARCHY=0 TWO_LAYER=1 "the no-hierarchy baseline is a single-layer benchmark path"
// (The setting side of the next one is `refuse bent_normals when=estimator==0`, which plan() meets
// first; the exclusion keeps those variants from being compiled.)
#pragma sao exclude BENT_NORMALS=1 ESTIMATOR=0 "bent normals come from the visibility estimator's slices: set estimator 1"
#pragma sao exclude BENT_NORMALS=1 OUTPUT_FORMAT=0 "bent normals need an rgba output (rgba8 or rgba16f) for the normal's three components and A"
#pragma sao exclude BENT_NORMALS=1 OUTPUT_FORMAT=1 "bent normals need an rgba output (rgba8 or rgba16f) for the normal's three components and A"

// ---------------------------------------------------------------------------------------------
// Resources
// ---------------------------------------------------------------------------------------------
#pragma sao resource depth     kind=input  format=depth "The user's depth: hardware depth (D16/D24/D32F, standard or reversed) or R32F linear camera-space z; AO-buffer size plus the guard band"
#pragma sao resource depth2    kind=input  format=depth when=TWO_LAYER "Second depth layer (deep G-buffer), same size and convention as depth"
#pragma sao resource normals   kind=input  format=rgba16f when=NORMALS_SUPPLIED "Normals, same size as depth: camera- or world-space .xyz (components in [-1,1]) or their signed octahedral map in .xy (sao::Camera::normalsEncoding)"
#pragma sao resource motion    kind=input  format=rg16f formats=[rg16f,rg32f,rgba16f,rgba32f] when=MOTION_VECTORS "Motion vectors, same size and region as depth: .xy the offset in pixels from this frame's texel to where its surface was in the previous frame (previous = current + motion; rows in the depth's order)"
#pragma sao resource csz       kind=image  format=r32f mips=auto extent=input "Camera-space z MIP chain (z < 0, +0.0 = sky), the depth input's size including the guard band"
#pragma sao resource csz2      kind=image  format=r32f mips=auto extent=input when=TWO_LAYER "Camera-space z MIP chain of the second layer"
#pragma sao resource width_run kind=image format=rg16f mips=auto extent=input when=THICKNESS_FROM_WIDTH "thickness_model 1: x, y each csz texel's thickness along that axis over thickness from its run on its own level (SAO_WIDTH_REACH of the level's texels each side), in (0, 1] (1 = wide), binary16-rounded by the width pass; width_resolve's input"
#pragma sao resource csz_share kind=image format=rg32f mips=auto extent=input when=THICKNESS_FROM_WIDTH "thickness_model 1: x each csz texel's z (csz's own bits), y its shares of thickness along x and y packed as binary16 (sao_pack_shares: packHalf2x16's bits read as a float, always a normal positive one), each that axis' thickness over thickness in (0, 1] (1 = wide), the first narrow width_run share among the texel and the texels above it in the chain (level m + 1's (x/2, y/2), ...), so a run wide at one level takes its width from a coarser one. A visibility tap reads its z and its thickness in one fetch"
#pragma sao resource ao_raw    kind=image  format=rg32f format_when=HALF_INTERMEDIATES:rg16f divide_by=resolution_divisor "x: visibility A after the 2x2 reconstruction, y: key = camera-space z times key_scale (+0.0 = sky); the viewport over resolution_divisor"
#pragma sao resource ao_low    kind=image  format=rg32f format_when=HALF_INTERMEDIATES:rg16f divide_by=resolution_divisor "(A, key) after the bilateral blur, the upsample's input (with blur_radius 0 the upsample reads ao_raw instead)"
#pragma sao resource history  kind=image  format=rgba32f divide_by=resolution_divisor when=TEMPORAL history=true "Temporal: x the accumulated obscurance sum, y its key z (+0.0 = sky), z the frames it holds (0 = none), w its normal (octahedral, 12 bits a component, as the integer qx*4096 + qy); ao_raw's size, two images that trade places every frame"
#pragma sao resource ao        kind=output format=r16f formats=[r16f,r8,rgba8,rgba16f] "Final ambient visibility A in [0,1] (1 = unoccluded), linear; r16f unless the caller's output image has another of formats= (OUTPUT_FORMAT); with output_blend multiply, the caller's texels times A"
// OpenGL ES 3.1 stores r32f, rgba16f, rgba32f and rgba8 but not r16f, rg16f, rg32f or r8 (GLSL ES
// 3.10, 4.4.7): on GLES each image of those formats takes the wider format below (the values do
// not change: the passes round A, the keys and the shares of thickness to binary16 themselves, so an r16f output
// stored as r32f holds the same values), and a caller's r8 output has no GLES form. Costs: docs/BENCHMARKS.md.
#pragma sao target gles storage=[r16f:r32f,rg16f:rgba16f,rg32f:rgba32f] refuse=[r8] "OpenGL ES 3.1 has no r16f, rg16f, rg32f or r8 storage images"

// ---------------------------------------------------------------------------------------------
// Shared library (pure functions; see each file)
// ---------------------------------------------------------------------------------------------
#include "include/sao_depth.glsl"
#include "include/sao_position.glsl"
#include "include/sao_normal.glsl"
#include "include/sao_zmip.glsl"
#include "include/sao_spiral.glsl"
#include "include/sao_estimator.glsl"
#include "include/sao_visibility.glsl"
#include "include/sao_bent.glsl"
#include "include/sao_blur.glsl"
#include "include/sao_upsample.glsl"
#include "include/sao_output.glsl"
#include "include/sao_temporal.glsl"

// ---------------------------------------------------------------------------------------------
// Parameter block: filled by host code from Settings + Camera + extents (docs/effect-math.md,
// "Parameter block"). Lengths are camera-space (view) units: metres times metersToViewUnits.
// std140 offsets in brackets; 400 bytes (392 of members, rounded up to a vec4).
// ---------------------------------------------------------------------------------------------
#pragma sao block SaoParams
layout(std140, binding = 0) uniform SaoParams {
    vec4  proj_info;            // [0]   eq. 3 (a_x, a_y, b_x, b_y): x_C = w*((x+0.5)*a_x + b_x), y_C = w*((y+0.5)*a_y + b_y), x,y = csz level-0 texel, w = z_C (perspective) or 1 (ortho); guard folded into b
    vec4  clip_info;            // [16]  eq. 2 (c0, c1, c2, 0): perspective z = c0/(d*c1 + c2); ortho / linear z = d*c1 + c2
    vec4  blur_weights_1_4;     // [32]  Gaussian blur weights w(1..4) (w(0) = 1 implicitly), 0 beyond blur_radius
    vec4  blur_weights_5_8;     // [48]  Gaussian blur weights w(5..8)
    float far_dir;              // [64]  sky test on the raw depth d: sky when d*far_dir >= far_lim (standard 1, reversed -1, linear 0)
    float far_lim;              // [68]  (standard 1, reversed 0, linear 1)
    int   depth_mode;           // [72]  SAO_DEPTH_MODE_PERSPECTIVE / _ORTHOGRAPHIC / _LINEAR
    int   ortho;                // [76]  1: orthographic projection (eq. 3 without the factor z, eq. 5 without 1/-z); 0: perspective
    float radius;               // [80]  r, view units
    float radius2;              // [84]  r*r
    float bias;                 // [88]  beta of eq. 1 (unitless)
    float intensity_div_s;      // [92]  2*sigma*r/s, r = radius in view units (eq. 1's term is 1/length, sigma is unitless)
    float epsilon;              // [96]  epsilon of eq. 1, view units squared
    float contrast;             // [100] k of eq. 1
    float proj_scale;           // [104] S' of eq. 5: pixels spanned by 1 view unit at z = -1 (perspective) or anywhere (ortho), > 0
    float inv_samples;          // [108] 1/s
    int   samples;              // [112] s, 1..SAO_MAX_SAMPLES
    int   spiral_turns;         // [116] tau of eq. 6 (host table, docs/effect-math.md)
    int   log_q;                // [120] log2 q' of eq. 9
    int   max_mip;              // [124] highest csz level taps may read (levels allocated - 1)
    float quad_edge_threshold;  // [128] 2x2 reconstruction z threshold, view units
    float blur_edge_sharpness;  // [132] bilateral depth weight scale per key unit: 1/view units, or 1/m with half_intermediates
    int   blur_radius;          // [136] R, taps each side, 0..SAO_MAX_BLUR_RADIUS
    int   blur_stride;          // [140] pixels between blur taps, >= 1
    ivec2 ao_size;              // [144] the viewport: size of ao (and of ao_raw, ao_low when ao_divisor = 1)
    ivec2 guard;                // [152] guard band: AO pixel p is csz / depth texel p + guard
    ivec2 input_offset;         // [160] texel of depth, depth2 and normals that holds csz texel (0, 0): the region inside a larger texture
    int   ao_divisor;           // [168] resolution_divisor d: reduced AO pixel p stands for viewport pixel min(p*d + d/2, ao_size - 1)
    int   output_mask;          // [172] output channels that receive A, bit 0 = R .. bit 3 = A (15: all); an RGBA output keeps the others
    float fade_start;           // [176] distance fade start, view units (-z); used only when fade_end > 0
    float fade_end;             // [180] distance fade end, view units: A = 1 from -z >= fade_end on; 0 = no fade
    float fade_inv_range;       // [184] 1/(fade_end - fade_start), 1/view units; 0 when there is no fade
    int   normals_encoding;     // [188] SAO_NORMALS_CAMERA_XYZ / _WORLD_XYZ / _CAMERA_OCTAHEDRAL / _WORLD_OCTAHEDRAL: how the normals input holds a normal
    vec4  view_x;               // [192] world -> camera rotation R, column 0 (.w = 0): n_camera = R n_world for the world encodings; identity otherwise
    vec4  view_y;               // [208] column 1
    vec4  view_z;               // [224] column 2
    int   output_blend;         // [240] SAO_OUTPUT_BLEND_REPLACE / _MULTIPLY: how the output's selected channels take A
    uint  frame_phase;          // [244] the frame's rotation of every pixel's spiral, in 2^-32 turns (0 at frame 0; sao::frameSpiral)
    float frame_alpha_offset;   // [248] the frame's radial tap position: alpha_i = (i + offset) / s (0.5 at frame 0, the paper's)
    int   depth_samples;        // [252] samples per texel of the depth input (1: single-sample; DEPTH_MULTISAMPLE reads 0..n-1)
    int   depth_sample_policy;  // [256] SAO_DEPTH_SAMPLE_0 / _NEAREST: which sample of a multisampled depth texel linear_z keeps
    uint  tap_turn0;            // [260] eq. 6 for tap 0: alpha_0*tau turns mod 1 in 2^-32 turns (sao::spiralTapTurn(0, s, tau)): the host's, so no pixel divides by s
    vec2  tap_step;             // [264] (cos, sin) of 2*pi*tau/s, the angle from one tap to the next (eq. 6): tap i+1's direction is tap i's rotated by it
    vec4  prev_from_cur_x;      // [272] temporal: this frame's camera space -> the previous frame's, row 0 (.xyz rotation, .w translation, view units); identity without history
    vec4  prev_from_cur_y;      // [288] row 1
    vec4  prev_from_cur_z;      // [304] row 2
    vec4  prev_proj_info;       // [320] temporal: proj_info of the previous frame's camera (eq. 3, guard folded in)
    float temporal_min_blend;   // [336] temporal: 1 - temporal_hysteresis, this frame's least share
    float temporal_max_frames;  // [340] temporal: 1 / (1 - temporal_hysteresis), the frames a history texel counts at most
    float temporal_depth_k;     // [344] temporal: 1 / temporal_depth_tolerance
    int   history_valid;        // [348] temporal: 1 when the history holds the previous frame (0 after create, a settings change, a resize, a reset)
    float key_scale;            // [352] the (A, key) images' key is z times this: 1, or with half_intermediates 1/metersToViewUnits (the key in metres)
    float key_to_view;          // [356] the key back in view units: 1, or metersToViewUnits
    int   multi_bounce;         // [360] 1: the output store applies Jimenez et al. 2016's multi-bounce fit to A (albedo > 0); 0: A as it is
    float bounce_a;             // [364] the fit's cubic coefficient, 2.0404*albedo - 0.3324 (0 when multi_bounce is 0)
    float bounce_b;             // [368] quadratic, -4.7951*albedo + 0.6417
    float bounce_c;             // [372] linear, 2.7552*albedo + 0.6903
    float thickness;            // [376] visibility estimator: T, view units (0 with estimator 0)
    float depth_tolerance;      // [380] visibility estimator: tol, relative to depth (0 with estimator 0)
    int   slices;               // [384] visibility estimator: slices per pixel, 1..SAO_MAX_SLICES (0 with estimator 0)
    uint  slice_turn;           // [388] visibility estimator: the angle between slices, 2^-32 turns (half a turn over slices)
    float thickness_min;        // [392] visibility estimator, thickness_model 1: SAO_WIDTH_MIN_M in view units; 0: thickness_model 0 (every slab thickness deep)
    float blur_edge_relative;   // [396] bilateral depth weight's part per |dz|/|z| (unitless: the same for any key unit)
    int   blur_edge_slope;      // [400] 1: a blur tap's key is compared with the centre's plane (sao_blur_slope); 0: with the centre's key
};

// ---------------------------------------------------------------------------------------------
// The z chain (paper Table 1, rotated grid): linear_z and linear_z2 write all of a layer's levels
// in one dispatch (levels=0..7: out_csz[m] is level m). Each invocation (texels=2x2) stores its
// 2x2 level-0 texels and their level-1 texel, then walks up: the texel of the next level that
// copies this one by the rotated grid gets its z too, and so on while each level's pick is this
// texel's copy, up to max_mip. Every texel above level 1 is the copy of exactly one level-1 texel,
// so exactly one invocation stores it, with the value the level-by-level chain gives it: no shared
// memory, no barrier, bit for bit (the CPU reference computes the chain level by level). Slots are
// constant indices: Vulkan needs shaderStorageImageArrayDynamicIndexing for any other. One chain
// per pass: eight image units, GL 4.3's minimum.
// ---------------------------------------------------------------------------------------------
#ifdef SAO_PASS_LEVEL_SLOTS
#if SAO_PASS_FIRST_LEVEL != 0 || SAO_PASS_LEVEL_SLOTS != SAO_MAX_MIP_LEVELS
#error "SAO_CHAIN_FROM_BLOCK writes a whole chain: levels=0..SAO_MAX_MIP_LEVELS-1"
#endif
#define SAO_CHAIN_UP(IMG, J, z) \
    if (sao_up && (J) <= max_mip) { sao_up = sao_rotated_grid_parent(sao_cur, sao_size); if (sao_up) imageStore(IMG[J], sao_cur, sao_texel4(z)); }
// Invocation b (texels=2x2): Z_OF(p) (a TYPE: float, or vec2) into the level-0
// texels 2b .. 2b + 1 that lie inside size0, then level-1 texel b, which copies one of them (the
// rotated grid picks inside the block, clamp included), then up from there.
#define SAO_CHAIN_FROM_BLOCK(IMG, b, size0, Z_OF, TYPE) { \
    TYPE sao_zb[4]; \
    for (int sao_k = 0; sao_k < 4; ++sao_k) { \
        ivec2 sao_p = 2 * (b) + ivec2(sao_k & 1, sao_k >> 1); \
        sao_zb[sao_k] = TYPE(0.0); \
        if (all(lessThan(sao_p, size0))) { \
            sao_zb[sao_k] = Z_OF(sao_p); \
            imageStore(IMG[0], sao_p, sao_texel4(sao_zb[sao_k])); \
        } \
    } \
    ivec2 sao_size = max((size0) >> 1, ivec2(1)); \
    if (max_mip >= 1 && all(lessThan(b, sao_size))) { \
        ivec2 sao_s = sao_rotated_grid_source(b, size0) - 2 * (b); \
        TYPE sao_z = sao_zb[sao_s.y * 2 + sao_s.x]; \
        imageStore(IMG[1], b, sao_texel4(sao_z)); \
        ivec2 sao_cur = b; \
        bool sao_up = true; \
        SAO_CHAIN_UP(IMG, 2, sao_z) \
        SAO_CHAIN_UP(IMG, 3, sao_z) \
        SAO_CHAIN_UP(IMG, 4, sao_z) \
        SAO_CHAIN_UP(IMG, 5, sao_z) \
        SAO_CHAIN_UP(IMG, 6, sao_z) \
        SAO_CHAIN_UP(IMG, 7, sao_z) \
    } \
}
// A chain texel as imageStore takes it.
vec4 sao_texel4(float z) { return vec4(z, 0.0, 0.0, 0.0); }
vec4 sao_texel4(vec2 v) { return vec4(v, 0.0, 0.0); }
// A chain pass's main: invocation b = the global id stores its block and the walk up, if its
// level-0 block starts inside IMG's level 0.
#define SAO_CHAIN_PASS(IMG, Z_OF, TYPE) { \
    ivec2 b = ivec2(gl_GlobalInvocationID.xy); \
    ivec2 size0 = imageSize(IMG[0]); \
    if (any(greaterThanEqual(2 * b, size0))) \
        return; \
    SAO_CHAIN_FROM_BLOCK(IMG, b, size0, Z_OF, TYPE); \
}
// Level J (>= 2) of IMG at texel p, J not a constant: stores with constant slot indices.
#define SAO_STORE_LEVEL(IMG, J, p, v) \
    if ((J) == 2) imageStore(IMG[2], p, v); else if ((J) == 3) imageStore(IMG[3], p, v); \
    else if ((J) == 4) imageStore(IMG[4], p, v); else if ((J) == 5) imageStore(IMG[5], p, v); \
    else if ((J) == 6) imageStore(IMG[6], p, v); else if ((J) == 7) imageStore(IMG[7], p, v);
// A chain whose texels are each computed on their own level rather than copied: LEVEL0_AT(p) on
// level 0, TEXEL_AT(p, m) above (apart, because llvmpipe runs a branch's body whether or not a lane
// takes it). Invocation b stores its level-0 texels 2b .. 2b + 1 inside size0 and level-1 texel b.
// The texels of levels 2 .. max_mip go to whole work groups, level by level (rows in order): a list
// of slots where each level takes a whole number of groups' worth (sao_level_slots), work group g
// taking slots 64 g .. 64 g + 63, then as many again one dispatch on, and so on. So no invocation
// walks up the levels (a walk up holds its group for every level's work: width 131 ms instead of 81
// at 1280x720 on llvmpipe), about one group in three has one texel a lane, and every store a group
// makes goes to one level: Vulkan wants an image array's index uniform in the group (lanes storing
// to two levels at once lost the stores of one of them on lavapipe).
int sao_level_slots(ivec2 size, int lanes) { return (size.x * size.y + lanes - 1) / lanes * lanes; }
#define SAO_LEVELS_PASS(IMG, LEVEL0_AT, TEXEL_AT) { \
    ivec2 b = ivec2(gl_GlobalInvocationID.xy); \
    ivec2 size0 = imageSize(IMG[0]); \
    if (all(lessThan(2 * b, size0))) { \
        for (int sao_k = 0; sao_k < 4; ++sao_k) { \
            ivec2 sao_p = 2 * b + ivec2(sao_k & 1, sao_k >> 1); \
            if (all(lessThan(sao_p, size0))) \
                imageStore(IMG[0], sao_p, sao_texel4(LEVEL0_AT(sao_p))); \
        } \
        if (max_mip >= 1 && all(lessThan(b, max(size0 >> 1, ivec2(1))))) \
            imageStore(IMG[1], b, sao_texel4(TEXEL_AT(b, 1))); \
    } \
    int sao_lanes = int(gl_WorkGroupSize.x * gl_WorkGroupSize.y); \
    ivec2 sao_groups = (size0 + 2 * ivec2(gl_WorkGroupSize.xy) - 1) / (2 * ivec2(gl_WorkGroupSize.xy)); \
    int sao_m = 2; \
    int sao_first = 0; /* level sao_m's first slot */ \
    ivec2 sao_sz = max(size0 >> 2, ivec2(1)); \
    for (int sao_s = int(gl_WorkGroupID.y) * sao_groups.x * sao_lanes + int(gl_WorkGroupID.x) * sao_lanes; \
         sao_m <= max_mip; sao_s += sao_groups.x * sao_groups.y * sao_lanes) { \
        while (sao_m <= max_mip && sao_s >= sao_first + sao_level_slots(sao_sz, sao_lanes)) { \
            sao_first += sao_level_slots(sao_sz, sao_lanes); \
            ++sao_m; \
            sao_sz = max(sao_sz >> 1, ivec2(1)); \
        } \
        int sao_i = sao_s - sao_first + int(gl_LocalInvocationIndex); \
        if (sao_m <= max_mip && sao_i < sao_sz.x * sao_sz.y) { \
            ivec2 sao_q = ivec2(sao_i % sao_sz.x, sao_i / sao_sz.x); \
            vec4 sao_v = sao_texel4(TEXEL_AT(sao_q, sao_m)); \
            SAO_STORE_LEVEL(IMG, sao_m, sao_q, sao_v) \
        } \
    } \
}
#endif

// ---------------------------------------------------------------------------------------------
// Pass 1: hardware depth -> camera-space z, MIP level 0 (eq. 2), and the chain above it. One
// invocation per 2x2 depth texels (one level-1 texel).
// ---------------------------------------------------------------------------------------------
#pragma sao pass linear_z entry=sao_linear_z_main local=8x8 texels=2x2 reads=depth writes=csz variants=DEPTH_MULTISAMPLE levels=0..7 "Camera-space z (eq. 2) into csz level 0 and the z MIP chain by rotated-grid subsampling (paper Table 1), in one dispatch; sky and invalid depth become +0.0 and stay sky; a multisampled depth texel gives the sample its policy picks"
// csz texel p's z (the host checked that the region lies inside the textures).
float sao_linear_z_texel(ivec2 p)
{
    ivec2 t = p + input_offset;
#if DEPTH_MULTISAMPLE
    // One sample stands for the texel: sample 0, or the nearest geometry (the largest z < 0; csz's
    // sky marker +0.0 is larger, so it is kept only when every sample is sky).
    float z = sao_z_from_depth(texelFetch(in_depth, t, 0).r, clip_info, depth_mode, far_dir, far_lim);
    if (depth_sample_policy == SAO_DEPTH_SAMPLE_NEAREST) {
        for (int s = 1; s < depth_samples; ++s) {
            float zs = sao_z_from_depth(texelFetch(in_depth, t, s).r, clip_info, depth_mode, far_dir, far_lim);
            z = sao_nearer_z(z, zs);
        }
    }
    return z;
#else
    return sao_z_from_depth(texelFetch(in_depth, t, 0).r, clip_info, depth_mode, far_dir, far_lim);
#endif
}

void sao_linear_z_main()
{
    SAO_CHAIN_PASS(out_csz, sao_linear_z_texel, float)
}
#pragma sao end

// ---------------------------------------------------------------------------------------------
// Pass 2 (TWO_LAYER only): the second layer's z and chain, as linear_z. A pass of its own, so that
// no dispatch binds more than eight storage images. Without TWO_LAYER it writes nothing, and the
// plan leaves out a pass that writes nothing.
// ---------------------------------------------------------------------------------------------
#pragma sao pass linear_z2 entry=sao_linear_z2_main local=8x8 texels=2x2 reads=depth2 writes=csz2 variants=TWO_LAYER levels=0..7 "Second depth layer only: camera-space z (eq. 2) into csz2 and its z MIP chain, as linear_z"
#if TWO_LAYER
float sao_linear_z2_texel(ivec2 p)
{
    return sao_z_from_depth(texelFetch(in_depth2, p + input_offset, 0).r, clip_info, depth_mode, far_dir, far_lim);
}
#endif

void sao_linear_z2_main()
{
#if TWO_LAYER
    SAO_CHAIN_PASS(out_csz2, sao_linear_z2_texel, float)
#endif
}
#pragma sao end

// ---------------------------------------------------------------------------------------------
// Pass 2b (THICKNESS_FROM_WIDTH only): each csz texel's share of thickness along x and y from its
// run of continuous depth (docs/effect-math.md 5.9) on its own level, once per texel, so that a tap
// costs no walk of its own (its z's texel of csz_share holds its shares). Level 0: a work group's 16x16 texels
// find their runs in shared memory: the 16 rows with SAO_WIDTH_REACH texels of halo left and right,
// the 16 columns with as many above and below, fetched by textureGather (six 2x2 quads an
// invocation); each invocation then takes 12 consecutive texels of a row and of a column (and the
// next one) and ors the links between them into the band's 32-bit words (bit i: the walk from band
// texel i to its neighbour continues); then each run's end is a bit scan (findLSB / findMSB over 16
// links), the walk of the CPU reference's runShare step for step. A texel above level 0 is walked
// by the invocation that writes it, texelFetches on its level (SAO_LEVELS_PASS: each invocation its
// level-1 texel, and one group in three a texel a lane of a level above). Without the variant it
// writes nothing and the plan leaves it out.
// ---------------------------------------------------------------------------------------------
#pragma sao pass width entry=sao_width_main local=8x8 texels=2x2 reads=csz writes=width_run variants=THICKNESS_FROM_WIDTH levels=0..7 "thickness_model 1 only: each csz texel's share of thickness along x and y from its run of continuous depth on its own level (up to SAO_WIDTH_REACH of the level's texels each side; level 0's found by bit scans in shared memory), into width_run's chain"
#if THICKNESS_FROM_WIDTH
#if SAO_WIDTH_REACH != 16
#error "the width pass's bands hold 16 texels of halo: one 16-bit scan per run end"
#endif
const int SAO_BAND = 48;  // a band's length: 16 texels of the tile and SAO_WIDTH_REACH each side
// The tile's bands: kind 0 the 16 rows (x from the tile's origin - 16), kind 1 the 16 columns (y
// from its origin - 16), clamped fetches: band texel i of band b of kind k at ((k * 16 + b) * 48 + i).
shared float sao_band_z[2 * 16 * SAO_BAND];
// Their links, two words per band (links 0..31, 32..46): bit i says the walk steps on from band
// texel i to i + 1 (direction 0, towards +x/+y) or from i + 1 to i (direction 1).
shared uint sao_band_links[2 * 2 * 16 * 2];

// Band b of kind k: its texel 0 in sao_band_z, and its direction d's word 0 in sao_band_links.
int sao_band_base(int k, int b) { return (k * 16 + b) * SAO_BAND; }
int sao_band_words(int k, int d, int b) { return ((k * 2 + d) * 16 + b) * 2; }

// Whether a walk steps on from z_from to z_next (at a texel inside the image or not): as the CPU
// reference's walk (runShare), a texel outside continues it (the walk then runs through its reach:
// wide).
bool sao_width_link(float z_from, float z_next, bool next_inside)
{
    precise float dz = abs(z_next - z_from);
    return !next_inside || (!sao_is_sky(z_next) && dz <= SAO_WIDTH_JUMP * abs(z_next));
}

// Quad q (0 <= q < 192) of the tile's bands of kind `kind`: the rows' 48x16 texels as 24x8 2x2
// quads, the columns' 16x48 as 8x24, each quad's four z (clamped to the image as clamp-to-edge
// does) into its two bands' texels. One gather fetches what four texelFetches did: llvmpipe pays
// per fetch call, a GPU per instruction.
void sao_width_gather(int kind, int q, ivec2 origin, ivec2 size0)
{
    // The quad's lower-left texel, in band coordinates (i along the band, b across it).
    int qi = 2 * (kind == 0 ? q % 24 : q / 8);
    int qb = 2 * (kind == 0 ? q / 24 : q % 8);
    ivec2 corner = kind == 0 ? origin + ivec2(qi - 16, qb) : origin + ivec2(qb, qi - 16);
    // The gather's footprint is the 2x2 texels around its coordinate: the shared corner of the four.
    vec4 z4 = textureGather(in_csz, vec2(corner + 1) / vec2(size0), 0);
    // textureGather's order: x (0, 1), y (1, 1), z (1, 0), w (0, 0) from the lower-left texel.
    float z00 = z4.w, z10 = z4.z, z01 = z4.x, z11 = z4.y;
    if (kind == 0) {  // bands qb, qb + 1 (rows), texels qi, qi + 1 (x)
        sao_band_z[sao_band_base(0, qb) + qi] = z00;
        sao_band_z[sao_band_base(0, qb) + qi + 1] = z10;
        sao_band_z[sao_band_base(0, qb + 1) + qi] = z01;
        sao_band_z[sao_band_base(0, qb + 1) + qi + 1] = z11;
    } else {  // bands qb, qb + 1 (columns), texels qi, qi + 1 (y)
        sao_band_z[sao_band_base(1, qb) + qi] = z00;
        sao_band_z[sao_band_base(1, qb) + qi + 1] = z01;
        sao_band_z[sao_band_base(1, qb + 1) + qi] = z10;
        sao_band_z[sao_band_base(1, qb + 1) + qi + 1] = z11;
    }
}

// Segment seg (texels 12 seg .. 12 seg + 11) of band `band` of kind `kind` (texel 0 at `first`
// in the image, along `step`): the links between its texels and to the next segment's first
// texel, both directions, from the band's z in shared memory, or'ed into the band's words (zeroed
// before).
void sao_width_segment(int kind, int band, int seg, ivec2 first, ivec2 size0)
{
    int base = sao_band_base(kind, band);
    int up = sao_band_words(kind, 0, band);
    int dn = sao_band_words(kind, 1, band);
    int pos0 = (kind == 0) ? first.x : first.y;  // texel 0 along the band's axis
    int size = (kind == 0) ? size0.x : size0.y;
    int i = 12 * seg;
    float zp = sao_band_z[base + i];
    uint bits_up = 0u;  // links i .. i + 11 of this segment, bit k = link 12 seg + k
    uint bits_dn = 0u;
    int n = min(12, SAO_BAND - 1 - i);
    for (int k = 0; k < n; ++k) {
        int j = i + k + 1;
        float zj = sao_band_z[base + j];
        int pj = pos0 + j;
        bool l_up = sao_width_link(zp, zj, pj >= 0 && pj < size);
        bool l_dn = sao_width_link(zj, zp, pj - 1 >= 0 && pj - 1 < size);
        bits_up |= l_up ? (1u << uint(k)) : 0u;
        bits_dn |= l_dn ? (1u << uint(k)) : 0u;
        zp = zj;
    }
    // Links 12 seg + k into words 0 (links 0..31) and 1 (32..46).
    uint sh = uint(i & 31);
    int w = i >> 5;
    atomicOr(sao_band_links[up + w], bits_up << sh);
    atomicOr(sao_band_links[dn + w], bits_dn << sh);
    if (w == 0 && i + 12 > 32) {
        atomicOr(sao_band_links[up + 1], bits_up >> (32u - sh));
        atomicOr(sao_band_links[dn + 1], bits_dn >> (32u - sh));
    }
}

// 16 links of a band from texel index `start` (0 <= start <= 31): bit k is link start + k.
uint sao_width_window(uint w0, uint w1, int start)
{
    uint lo = w0 >> uint(start);
    uint hi = (start == 0) ? 0u : (w1 << uint(32 - start));
    return (lo | hi) & 0xFFFFu;
}

// The share of the tile texel at index 16 + t of band `band` of kind `kind` (0: along x, its row;
// 1: along y, its column); `first` is the band's texel 0 in the image, `step` its axis.
float sao_width_band_share(int kind, int band, int t, ivec2 first, ivec2 step, float z)
{
    int base = sao_band_base(kind, band);
    int up = sao_band_words(kind, 0, band);
    int dn = sao_band_words(kind, 1, band);
    int i0 = 16 + t;
    // Towards +: links i0 .. i0 + 15, the first broken one (lowest clear bit) is the run's end.
    uint stop_up = ~sao_width_window(sao_band_links[up], sao_band_links[up + 1], i0) & 0xFFFFu;
    // Towards -: links i0 - 1 down to i0 - 16 (bits 15 .. 0 of the window from i0 - 16).
    uint stop_dn = ~sao_width_window(sao_band_links[dn], sao_band_links[dn + 1], i0 - 16) & 0xFFFFu;
    bool wide = stop_up == 0u || stop_dn == 0u;
    int e_up = wide ? i0 : i0 + findLSB(stop_up);           // the last texel: the broken link's own
    int e_dn = wide ? i0 : i0 - 16 + findMSB(stop_dn) + 1;  // the texel after the broken link
    return sao_run_share_of(first + e_dn * step, sao_band_z[base + e_dn], first + e_up * step, sao_band_z[base + e_up],
                            wide, z, kind == 0, proj_info, ortho, thickness, thickness_min, 1.0);
}

// Level-0 texel p of the work group's tile: its shares along x and y (1 for sky: never read, a sky
// tap blocks nothing), rounded here, so that the stored bits do not depend on the driver's
// float-to-half conversion.
vec2 sao_width_texel(ivec2 p)
{
    ivec2 origin = 16 * ivec2(gl_WorkGroupID.xy);
    ivec2 t = p - origin;
    float z = sao_band_z[sao_band_base(0, t.y) + 16 + t.x];
    if (sao_is_sky(z) || !(thickness > 0.0))
        return vec2(1.0);
    float sx = sao_width_band_share(0, t.y, t.x, origin + ivec2(-16, t.y), ivec2(1, 0), z);
    float sy = sao_width_band_share(1, t.x, t.y, origin + ivec2(t.x, -16), ivec2(0, 1), z);
    return vec2(sao_round_to_half(sx), sao_round_to_half(sy));
}

// Texel p of csz level m >= 1 (size0: level 0's size): its share along x (x_axis) or y from its
// run walked on level m itself, SAO_WIDTH_REACH of the level's texels each side (the CPU
// reference's runShare with m): continuity |dz| <= SAO_WIDTH_JUMP * 2^m * |z| (per level-0 texel, as
// level 0's), the ends at the level-0 texels their z came from, a texel's footprint 2^m.
float sao_width_level_share(ivec2 p, int m, float z, bool x_axis, ivec2 size0)
{
    ivec2 size = max(size0 >> m, ivec2(1));
    ivec2 step = x_axis ? ivec2(1, 0) : ivec2(0, 1);
    float span = float(1 << m);
    bool wide = false;
    ivec2 e[2];
    float ez[2];
    for (int side = 0; side < 2; ++side) {
        ivec2 d = (side == 0) ? step : -step;
        ivec2 last = p;
        float zp = z;
        bool walking = true;
        for (int k = 1; k <= SAO_WIDTH_REACH && walking; ++k) {
            ivec2 q = p + k * d;
            bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
            wide = wide || !inside;
            float zq = texelFetch(in_csz, clamp(q, ivec2(0), size - 1), m).r;
            precise float dz = abs(zq - zp);
            walking = inside && !sao_is_sky(zq) && dz <= SAO_WIDTH_JUMP * span * abs(zq);
            if (walking) {
                last = q;
                zp = zq;
            }
        }
        wide = wide || walking;
        e[side] = last;
        ez[side] = zp;
    }
    return sao_run_share_of(sao_mip_source(e[0], m, size0), ez[0], sao_mip_source(e[1], m, size0), ez[1], wide, z,
                            x_axis, proj_info, ortho, thickness, thickness_min, span);
}

// width_run's texel p of level m >= 1, from its own walk (level 0's: sao_width_texel, the bands).
vec2 sao_width_level_texel(ivec2 p, int m)
{
    float z = texelFetch(in_csz, p, m).r;
    if (sao_is_sky(z) || !(thickness > 0.0))
        return vec2(1.0);
    ivec2 size0 = textureSize(in_csz, 0);
    float sx = sao_width_level_share(p, m, z, true, size0);
    float sy = sao_width_level_share(p, m, z, false, size0);
    return vec2(sao_round_to_half(sx), sao_round_to_half(sy));
}
#endif

void sao_width_main()
{
#if THICKNESS_FROM_WIDTH
    ivec2 size0 = imageSize(out_width_run[0]);
    ivec2 origin = 16 * ivec2(gl_WorkGroupID.xy);
    int li = int(gl_LocalInvocationIndex);
    // Invocation li: quads li, li + 64 and li + 128 of each kind's bands (six gathers), and zeroes
    // two words of links; then segment li & 3 of band li >> 2 of each kind, its links or'ed into
    // the band's words.
    sao_band_links[2 * li] = 0u;
    sao_band_links[2 * li + 1] = 0u;
    for (int k = 0; k < 3; ++k) {
        sao_width_gather(0, li + 64 * k, origin, size0);
        sao_width_gather(1, li + 64 * k, origin, size0);
    }
    memoryBarrierShared();
    barrier();
    {
        int band = li >> 2;
        int seg = li & 3;
        sao_width_segment(0, band, seg, origin + ivec2(-16, band), size0);
        sao_width_segment(1, band, seg, origin + ivec2(band, -16), size0);
    }
    memoryBarrierShared();
    barrier();
    SAO_LEVELS_PASS(out_width_run, sao_width_texel, sao_width_level_texel)
#endif
}
#pragma sao end

// ---------------------------------------------------------------------------------------------
// Pass 2c (THICKNESS_FROM_WIDTH only): csz_share from csz and width_run. A run that is wide on its own
// level (it goes on through SAO_WIDTH_REACH texels) takes the share of the texel above it, level
// by level, until one is narrow: a level-0 run is then wide only where it is wide at every level up
// to max_mip (16 * 2^max_mip level-0 texels each side). Along x and y apart. Without the variant it
// writes nothing and the plan leaves it out. Each texel's z goes beside its shares, so that a
// visibility tap fetches one texel (rg32f) instead of csz's and a shares texel's: two surfaces
// read at the same texels double the cache lines in flight (docs/BENCHMARKS.md, the traffic model).
// ---------------------------------------------------------------------------------------------
#pragma sao pass width_resolve entry=sao_width_resolve_main local=8x8 texels=2x2 reads=csz,width_run writes=csz_share variants=THICKNESS_FROM_WIDTH levels=0..7 "thickness_model 1 only: each texel of each level of csz_share, its csz z and, along x and y, the first narrow width_run share among the texel and the texels above it ((x/2, y/2) at the next level, and so on up to max_mip), packed"
#if THICKNESS_FROM_WIDTH
vec2 sao_width_resolved_texel(ivec2 p, int m)
{
    float z = texelFetch(in_csz, p, m).r;
    vec2 s = texelFetch(in_width_run, p, m).rg;
    ivec2 q = p;
    ivec2 size = max(textureSize(in_width_run, 0) >> m, ivec2(1));
    for (int j = m + 1; j <= max_mip && (s.x >= 1.0 || s.y >= 1.0); ++j) {
        size = max(size >> 1, ivec2(1));
        q = min(q >> 1, size - 1);
        vec2 a = texelFetch(in_width_run, q, j).rg;
        s = vec2(s.x >= 1.0 ? a.x : s.x, s.y >= 1.0 ? a.y : s.y);
    }
    return vec2(z, sao_pack_shares(s));
}
vec2 sao_width_resolved_level0(ivec2 p) { return sao_width_resolved_texel(p, 0); }
#endif

void sao_width_resolve_main()
{
#if THICKNESS_FROM_WIDTH
    SAO_LEVELS_PASS(out_csz_share, sao_width_resolved_level0, sao_width_resolved_texel)
#endif
}
#pragma sao end

// ---------------------------------------------------------------------------------------------
// Pass 3: spiral taps (eq. 5-10) through the AlchemyAO estimator (eq. 1), or with ESTIMATOR the
// visibility estimator's slices over the same z hierarchy (sao_visibility.glsl), then the 2x2
// bilateral reconstruction through shared memory (no derivative instructions). One invocation
// per AO pixel; invocations outside the AO buffer take part in the barriers as sky. Two passes
// share the body: ao_sample stores (A, key) for the blur, the upsample or the output pass,
// ao_sample_output (when nothing follows: no blur, full resolution, no temporal history) stores A
// into the output itself.
// ---------------------------------------------------------------------------------------------
#if defined(SAO_PASS_AO_SAMPLE) || defined(SAO_PASS_AO_SAMPLE_OUTPUT)
#ifdef SAO_PASS_AO_SAMPLE_OUTPUT
// ao_sample_output lists neither (with temporal accumulation ao_sample runs, writing the history);
// GLSL's #if does not take an undefined name as 0.
#define TEMPORAL 0
#define MOTION_VECTORS 0
#else
#define BENT_NORMALS 0  // ao_sample does not list it: the blur and the upsample carry A only
#endif
#if SAO_TARGET_VULKAN
// The tap loops' trip counts (= samples, slices) as push constants: Mesa lavapipe 22.3 keeps ~0.4 MB of
// host memory per dispatch of a loop whose trip count comes from the uniform block its body also
// reads (docs/ROBUSTNESS.md, issue 19). The Vulkan backend pushes the block's samples and slices.
layout(push_constant) uniform SaoLoopCounts { int samples; int slices; } sao_loop;
#define SAO_TAP_COUNT sao_loop.samples
#define SAO_SLICE_COUNT sao_loop.slices
#else
#define SAO_TAP_COUNT samples
#define SAO_SLICE_COUNT slices
#endif
#if TWO_LAYER
#define SAO_CSZ2 in_csz2
#else
#define SAO_CSZ2 in_csz  // not read (two_layer false): a bound sampler of the right type
#endif
#if THICKNESS_FROM_WIDTH
#define SAO_CSZ_SHARE in_csz_share
#else
#define SAO_CSZ_SHARE in_csz  // not read (no THICKNESS_FROM_WIDTH): a bound sampler of the right type
#endif
shared float sao_quad_a[gl_WorkGroupSize.x * gl_WorkGroupSize.y];  // A per invocation
shared float sao_quad_h[gl_WorkGroupSize.x * gl_WorkGroupSize.y];  // A after the horizontal step
shared float sao_quad_z[gl_WorkGroupSize.x * gl_WorkGroupSize.y];  // key z (+0.0 = sky / outside)

// A of AO pixel p (of the reduced image when ao_divisor > 1) after the 2x2 reconstruction, and its
// key z in key_z (+0.0 = sky or outside); with TEMPORAL also this frame's history texel, stored.
// Every invocation of the group calls it (it holds the barriers); `inside` says whether p is stored.
// With BENT_NORMALS `bent` is the pixel's bent normal (camera space; 0 for sky and outside), not
// reconstructed; otherwise 0.
float sao_ao_sample(ivec2 p, bool inside, out float key_z, out vec3 bent)
{
    bent = vec3(0.0);
    ivec2 size0 = textureSize(in_csz, 0);
    ivec2 f = sao_low_representative(p, ao_divisor, ao_size);  // its viewport pixel (p itself at d = 1)
    ivec2 c = clamp(f + guard, ivec2(0), size0 - 1);  // csz level-0 texel
    float zc = texelFetch(in_csz, c, 0).r;

    float A = 1.0;
    float key = 0.0;
#if TEMPORAL
    float kept = 0.0;    // this frame's history texel: the accumulated sum, the frames it holds
    float frames = 0.0;  // (none for sky and outside) and the packed normal
    float normal_code = 0.0;
#endif
    if (inside && !sao_is_sky(zc)) {
        vec3 C = sao_position(vec2(c) + 0.5, zc, proj_info, ortho);
#if NORMALS_SUPPLIED
        vec3 n = sao_supplied_normal(texelFetch(in_normals, c + input_offset, 0), normals_encoding, view_x, view_y,
                                     view_z);
#else
        vec3 n = sao_reconstruct_normal(in_csz, c, C, proj_info, ortho);
#endif
        float r_px = sao_screen_radius(radius, proj_scale, zc, ortho);
        uint phase = sao_pixel_phase(uvec2(p)) + frame_phase;  // eq. 8, turned by the frame's rotation
        int s = clamp(SAO_TAP_COUNT, 1, SAO_MAX_SAMPLES);
#if ESTIMATOR
        // The visibility estimator: "sum" is the occlusion 1 - V (intensity_div_s = sigma), so that
        // sao_visibility gives max(0, 1 - sigma (1 - V))^k and TEMPORAL blends the occlusion. Radial
        // jitter: the frame's offset plus the pixel's hash, mod 1.
        float xi = fract(frame_alpha_offset + sao_pixel_jitter(uvec2(p)));
        vec3 moment;
        float sum = sao_visibility_occlusion(in_csz, SAO_CSZ2, SAO_CSZ_SHARE, TWO_LAYER != 0, Z_HIERARCHY != 0, c, C,
                                             n, r_px, phase, xi, s, SAO_SLICE_COUNT, slice_turn, proj_info, ortho,
                                             radius2, depth_tolerance, thickness, log_q, max_mip,
                                             BENT_NORMALS != 0, moment);
#if BENT_NORMALS
        bent = sao_bent_normal(moment, n);
#endif
#else
        float sum = 0.0;
        vec2 u = sao_turn_direction(tap_turn0 + phase);  // tap 0's direction; each tap turns it by tap_step
        int i = 0;  // s >= 1: a do-while, whose body llvmpipe does not run once more masked
        do {
            float h;
            ivec2 tap = sao_spiral_tap(c, i, inv_samples, frame_alpha_offset, u, r_px, h);
            u = sao_spiral_step(u, tap_step);
#if Z_HIERARCHY
            int m = sao_mip_level(h, log_q, max_mip);
#else
            int m = 0;
#endif
            ivec2 t = sao_mip_texel(tap, m, size0);
            vec2 q = vec2(tap) + 0.5;
            float o = sao_tap_obscurance(C, n, q, texelFetch(in_csz, t, m).r, proj_info, ortho,
                                         radius2, bias, epsilon);
#if TWO_LAYER
            o = max(o, sao_tap_obscurance(C, n, q, texelFetch(in_csz2, t, m).r, proj_info, ortho,
                                          radius2, bias, epsilon));
#endif
            sum += o;
        } while (++i < s);
#endif
#if TEMPORAL
        // Where this surface was in the previous frame: through the cameras, or by the motion input.
        vec3 P = sao_to_previous(C, prev_from_cur_x, prev_from_cur_y, prev_from_cur_z);
#if MOTION_VECTORS
        vec2 previous = (vec2(c) + 0.5) + texelFetch(in_motion, c + input_offset, 0).xy;
#else
        vec2 previous = sao_previous_pixel(P, prev_proj_info, ortho);
#endif
        // The pixel's normal in the previous camera: the history's normals are that camera's.
        vec3 nP = sao_rotate_to_previous(n, prev_from_cur_x, prev_from_cur_y, prev_from_cur_z);
        vec2 acc = sao_temporal_accumulate(in_history, previous, P.z, nP, NORMALS_SUPPLIED != 0, sum, guard, ao_divisor,
                                           temporal_depth_k, temporal_min_blend, temporal_max_frames, history_valid);
        normal_code = sao_pack_normal(n);
        sum = acc.x;
        kept = acc.x;
        frames = acc.y;
#endif
        A = sao_fade(sao_visibility(sum, intensity_div_s, contrast), zc, fade_start, fade_end, fade_inv_range);
        key = zc;
    }
#if TEMPORAL
    if (inside)
        imageStore(out_history, p, vec4(kept, key, frames, normal_code));
#endif

    // 2x2 bilateral reconstruction: quads are aligned to even pixels and lie inside one work
    // group (even local size). Every invocation reaches both barriers.
    uint li = gl_LocalInvocationIndex;
    uvec2 l = gl_LocalInvocationID.xy;
    uint lx = (l.y * gl_WorkGroupSize.x) + (l.x ^ 1u);  // quad neighbour along x
    uint ly = ((l.y ^ 1u) * gl_WorkGroupSize.x) + l.x;  // quad neighbour along y
    sao_quad_a[li] = A;
    sao_quad_z[li] = key;
    memoryBarrierShared();
    barrier();
    float a_h = sao_quad_mix(A, key, sao_quad_a[lx], sao_quad_z[lx], quad_edge_threshold);
    sao_quad_h[li] = a_h;
    memoryBarrierShared();
    barrier();
    key_z = key;
    return sao_quad_mix(a_h, key, sao_quad_h[ly], sao_quad_z[ly], quad_edge_threshold);
}
#endif

#pragma sao pass ao_sample entry=sao_ao_main local=8x8 reads=csz,csz2,csz_share,normals,history,motion writes=ao_raw,history variants=NORMALS_SUPPLIED,TWO_LAYER,Z_HIERARCHY,TEMPORAL,MOTION_VECTORS,HALF_INTERMEDIATES,ESTIMATOR,THICKNESS_FROM_WIDTH skip_when=direct_output==true "Obscurance from s spiral taps over the z hierarchy (eq. 1, 3-10), with TEMPORAL blended with the reprojected history (and this frame's history written), 2x2 bilateral reconstruction; writes (A, key z)"
void sao_ao_main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(p, min(ao_size, imageSize(out_ao_raw))));
    float key;
    vec3 bent;  // BENT_NORMALS is 0 here
    float a = sao_ao_sample(p, inside, key, bent);
#if HALF_INTERMEDIATES
    vec2 stored = sao_half_texel(vec2(a, key * key_scale));
#else
    vec2 stored = vec2(a, key);
#endif
    if (inside)
        imageStore(out_ao_raw, p, vec4(stored, 0.0, 0.0));
}
#pragma sao end

#pragma sao pass ao_sample_output entry=sao_ao_output_main local=8x8 reads=csz,csz2,csz_share,normals writes=ao variants=NORMALS_SUPPLIED,TWO_LAYER,Z_HIERARCHY,OUTPUT_FORMAT,ESTIMATOR,THICKNESS_FROM_WIDTH,BENT_NORMALS skip_when=direct_output==false "No blur at full resolution without temporal only: ao_sample's obscurance and 2x2 reconstruction, A stored straight into the output's format (no ao_raw, no output pass)"
void sao_ao_output_main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(p, min(ao_size, imageSize(out_ao))));
    float key;
    vec3 bent;
    float a = sao_ao_sample(p, inside, key, bent);
#if BENT_NORMALS
    if (inside)
        SAO_STORE_BENT_OUTPUT(p, bent, a);
#else
    if (inside)
        SAO_STORE_OUTPUT(p, a);
#endif
}
#pragma sao end

// ---------------------------------------------------------------------------------------------
// Pass 4: the separable bilateral blur (paper section 2.4), both directions in one dispatch. A work
// group covers 8 columns x 32 rows (texels=1x4); it blurs the rows those need (its own and
// blur_radius * blur_stride above and below) horizontally into shared memory, every invocation
// taking a share, then after the one barrier each invocation blurs its four texels vertically
// from there. The horizontal results stay float in shared memory (no ao_blur_h image, no second
// dispatch); each value is the one a horizontal pass over the whole image would give.
// ---------------------------------------------------------------------------------------------
#pragma sao pass blur entry=sao_blur_main local=8x8 texels=1x4 reads=ao_raw writes=ao_low variants=HALF_INTERMEDIATES skip_when=blur_radius==0 "Depth-aware Gaussian blur, horizontal then vertical in one dispatch through shared memory, into (A, key) for the upsample"
const int SAO_BLUR_COLS = int(gl_WorkGroupSize.x);
const int SAO_BLUR_TEXELS_Y = 4;  // texels=1x4
const int SAO_BLUR_ROWS = int(gl_WorkGroupSize.y) * SAO_BLUR_TEXELS_Y;
const int SAO_BLUR_HALO = SAO_MAX_BLUR_RADIUS * SAO_MAX_BLUR_STRIDE;
shared vec2 sao_blur_tile[SAO_BLUR_COLS * (SAO_BLUR_ROWS + 2 * SAO_BLUR_HALO)];  // (A, key) blurred along x

// The vertical blur of tile column `col` at tile row `row`: the taps of sao_bilateral_blur along
// (0, 1), read from the horizontally blurred rows in shared memory (rows off the image hold sky,
// so the sky test skips them), branch-free like it.
vec2 sao_blur_tile_column(int col, int row, int R, int stride)
{
    vec2 centre = sao_blur_tile[row * SAO_BLUR_COLS + col];
    float k = sao_blur_sharpness(centre.y, blur_edge_sharpness, blur_edge_relative);
    // Rows off the image hold sky: no slope there.
    float g = blur_edge_slope != 0 ? sao_blur_slope(sao_blur_tile[(row - stride) * SAO_BLUR_COLS + col].y, centre.y,
                                                    sao_blur_tile[(row + stride) * SAO_BLUR_COLS + col].y)
                                   : 0.0;
    float sum = 0.0;
    float wsum = 0.0;
    int t = -R;
    do {
        vec2 tap = sao_blur_tile[(row + t * stride) * SAO_BLUR_COLS + col];
        float w = sao_is_sky(tap.y) ? 0.0
                                    : sao_blur_weight(t, tap.y, centre.y + float(t) * g, k, blur_weights_1_4,
                                                      blur_weights_5_8);
        sum += w * tap.x;
        wsum += w;
    } while (++t <= R);
    return sao_is_sky(centre.y) ? vec2(1.0, 0.0) : vec2(sum / wsum, centre.y);
}

void sao_blur_main()
{
    ivec2 size = textureSize(in_ao_raw, 0);
    int R = clamp(blur_radius, 0, SAO_MAX_BLUR_RADIUS);
    int stride = clamp(blur_stride, 1, SAO_MAX_BLUR_STRIDE);
    int halo = R * stride;
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * ivec2(SAO_BLUR_COLS, SAO_BLUR_ROWS);
    int count = SAO_BLUR_COLS * (SAO_BLUR_ROWS + 2 * halo);
    int n = int(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    int i = int(gl_LocalInvocationIndex);  // < n <= count: a do-while (see sao_bilateral_blur)
    do {
        ivec2 q = origin + ivec2(i % SAO_BLUR_COLS, i / SAO_BLUR_COLS - halo);
        vec2 h = vec2(1.0, 0.0);  // rows off the image: sky, which the vertical taps skip
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)))
            h = sao_bilateral_blur(in_ao_raw, q, ivec2(1, 0), R, stride, blur_edge_sharpness, blur_edge_relative,
                                   blur_edge_slope != 0, blur_weights_1_4, blur_weights_5_8);
        sao_blur_tile[i] = h;
        i += n;
    } while (i < count);
    memoryBarrierShared();
    barrier();  // every invocation reaches it: the size tests come after
    ivec2 out_size = imageSize(out_ao_low);
    int col = int(gl_LocalInvocationID.x);
    for (int k = 0; k < SAO_BLUR_TEXELS_Y; ++k) {
        int local_row = int(gl_LocalInvocationID.y) + k * int(gl_WorkGroupSize.y);
        ivec2 p = origin + ivec2(col, local_row);
        if (any(greaterThanEqual(p, out_size)))
            continue;
        vec2 r = sao_blur_tile_column(col, local_row + halo, R, stride);
#if HALF_INTERMEDIATES
        r = sao_half_texel(r);
#endif
        imageStore(out_ao_low, p, vec4(r, 0.0, 0.0));
    }
}
#pragma sao end

// ---------------------------------------------------------------------------------------------
// Pass 5 (full resolution after ao_sample: with a blur, or with temporal accumulation, whose history
// ao_sample writes; otherwise ao_sample_output wrote the output): each pixel's A into the output,
// rounded in the shader as the output format holds it (sky texels hold A = 1).
// ---------------------------------------------------------------------------------------------
#pragma sao pass output entry=sao_output_main local=8x8 reads=ao_low writes=ao variants=OUTPUT_FORMAT skip_when=copy_to_output==false alias_when=blur_radius==0:ao_low=ao_raw "Full resolution, after ao_sample: A of the blurred (A, key) image (ao_raw without blur: temporal) into the output's format"
void sao_output_main()
{
    ivec2 x = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(x, imageSize(out_ao))))
        return;
    SAO_STORE_OUTPUT(x, texelFetch(in_ao_low, x, 0).x);
}
#pragma sao end

// ---------------------------------------------------------------------------------------------
// Pass 6 (reduced resolution only): joint bilateral upsample of (A, key) to the viewport, guided
// by csz level 0; writes the final A, rounded in the shader as the output format holds it.
// ---------------------------------------------------------------------------------------------
#pragma sao pass upsample entry=sao_upsample_main local=8x8 texels=2x2 reads=ao_low,csz writes=ao variants=OUTPUT_FORMAT skip_when=resolution_divisor==1 alias_when=blur_radius==0:ao_low=ao_raw "Reduced resolution only: depth-aware upsample to the full-resolution output (bilinear x relative-z weights over the 2x2 nearest low texels, else the nearest in z of the 3x3)"
// An invocation (texels=2x2) covers viewport pixels 2b .. 2b + 1. With d = 2 or 4 they lie in one low
// texel c = 2b >> log2(d), and every low texel any of them reads (its 2x2 bracketing texels and the
// 3x3 fallback) is one of the 3x3 around c, clamped into the image (docs/effect-math.md 6.4): the
// invocation fetches those nine once, with no shared memory and no barrier.

// One of a 2x2 block of the 3x3: a (top left), b, c, d in row order. Selects, not a dynamic index
// into the array: that puts it in memory (lavapipe: the pass 3.5x slower).
vec2 sao_up_pick(vec2 a, vec2 b, vec2 c, vec2 d, bool right, bool down)
{
    return down ? (right ? d : c) : (right ? b : a);
}

// A at viewport pixel x (csz z) from the 3x3 n around its low texel c: the 2x2 low texels whose
// representative pixels bracket x, weighted bilinearly by x's place between those pixels times the
// depth weight; all sky gives 1. `unmatched` is true for a geometry pixel none of the four matches
// in z (a silhouette, or a thin object the reduced image missed): its A is then
// sao_upsample_nearest_z's, so that no average of the two sides makes a halo. d is a power of two:
// shifts stand for its divisions and products.
float sao_upsample_bilinear(ivec2 x, float z, int d, ivec2 last, ivec2 c, vec2 n[9], out bool unmatched)
{
    unmatched = false;
    if (sao_is_sky(z))
        return 1.0;
    int sh = findMSB(d);
    ivec2 q0 = min(max(x - (d >> 1), ivec2(0)) >> sh, last);
    ivec2 q1 = min(q0 + 1, last);
    ivec2 r0 = sao_low_representative(q0, d, ao_size);
    ivec2 r1 = sao_low_representative(q1, d, ao_size);
    vec2 t = clamp(vec2(x - r0) / vec2(max(r1 - r0, ivec2(1))), 0.0, 1.0);
    float k = SAO_UPSAMPLE_Z_SHARPNESS / -z;
    // n[(q - c + 1).y * 3 + (q - c + 1).x] is texel q: q0 is c - 1 or c, q1 is c or c + 1 per axis.
    bvec2 e0 = equal(q0, c);
    bvec2 e1 = greaterThan(q1, c);
    vec2 s00 = sao_up_pick(n[0], n[1], n[3], n[4], e0.x, e0.y);
    vec2 s10 = sao_up_pick(n[1], n[2], n[4], n[5], e1.x, e0.y);
    vec2 s01 = sao_up_pick(n[3], n[4], n[6], n[7], e0.x, e1.y);
    vec2 s11 = sao_up_pick(n[4], n[5], n[7], n[8], e1.x, e1.y);
    float w00 = ((1.0 - t.x) * (1.0 - t.y)) * sao_upsample_depth_weight(z, s00.y, k);
    float w10 = (t.x * (1.0 - t.y)) * sao_upsample_depth_weight(z, s10.y, k);
    float w01 = ((1.0 - t.x) * t.y) * sao_upsample_depth_weight(z, s01.y, k);
    float w11 = (t.x * t.y) * sao_upsample_depth_weight(z, s11.y, k);
    float wsum = ((w00 + w10) + w01) + w11;
    unmatched = !(wsum > 0.0);
    return unmatched ? 1.0 : (((w00 * s00.x + w10 * s10.x) + w01 * s01.x) + w11 * s11.x) / wsum;
}

// A of a geometry pixel at z that no bracketing texel matches: the 3x3, each within 1/SHARPNESS
// (relative) of the nearest z weighted linearly down to 0 at that distance; all sky gives 1. Texels
// of equal z (a receding floor's row) share the pixel: a single nearest texel, first in row order on
// ties, made the choice hang on the last bit of z (the same scene in mm gave other texels' A).
float sao_upsample_nearest_z(float z, vec2 n[9])
{
    float k = SAO_UPSAMPLE_Z_SHARPNESS / -z;
    float best = -1.0;
    for (int i = 0; i < 9; ++i)
        if (!sao_is_sky(n[i].y))
            best = (best < 0.0) ? abs(z - n[i].y) : min(best, abs(z - n[i].y));
    if (best < 0.0)
        return 1.0;
    float sum = 0.0;
    float vsum = 0.0;
    for (int i = 0; i < 9; ++i)
        if (!sao_is_sky(n[i].y)) {
            float v = max(0.0, 1.0 - k * (abs(z - n[i].y) - best));
            sum += v * n[i].x;
            vsum += v;
        }
    return sum / vsum;
}

void sao_upsample_main()
{
    ivec2 x0 = 2 * ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(out_ao);
    if (any(greaterThanEqual(x0, size)))
        return;
    int d = ao_divisor;  // 2 or 4 (skip_when: the pass never runs at 1)
    ivec2 last = textureSize(in_ao_low, 0) - 1;
    ivec2 c = min(x0 >> findMSB(d), last);
    vec2 n[9];
    for (int i = 0; i < 9; ++i) {
        ivec2 q = clamp(c + ivec2(i % 3 - 1, i / 3 - 1), ivec2(0), last);
        n[i] = texelFetch(in_ao_low, q, 0).xy * vec2(1.0, key_to_view);  // the key back in view units
    }
    // The 2x2 pixels (those past the image's edge read the edge's z and are not stored).
    ivec2 x1 = x0 + ivec2(1, 0);
    ivec2 x2 = x0 + ivec2(0, 1);
    ivec2 x3 = x0 + ivec2(1, 1);
    float z0 = texelFetch(in_csz, x0 + guard, 0).r;
    float z1 = texelFetch(in_csz, min(x1, size - 1) + guard, 0).r;
    float z2 = texelFetch(in_csz, min(x2, size - 1) + guard, 0).r;
    float z3 = texelFetch(in_csz, min(x3, size - 1) + guard, 0).r;
    bool u0, u1, u2, u3;
    float a0 = sao_upsample_bilinear(x0, z0, d, last, c, n, u0);
    float a1 = sao_upsample_bilinear(x1, z1, d, last, c, n, u1);
    float a2 = sao_upsample_bilinear(x2, z2, d, last, c, n, u2);
    float a3 = sao_upsample_bilinear(x3, z3, d, last, c, n, u3);
    // The unmatched pixels' fallback, one pixel per trip. A software rasteriser (llvmpipe) runs a
    // branch's body for every pixel but a loop only as often as its busiest lane needs (at least
    // once): the fallback, rarely needed, runs about once per invocation instead of four times.
    uint pending = (u0 ? 1u : 0u) | (u1 ? 2u : 0u) | (u2 ? 4u : 0u) | (u3 ? 8u : 0u);
    do {
        int j = findLSB(pending | 16u);  // 4: none left (the trip that always runs stores nothing)
        float a = sao_upsample_nearest_z(j == 0 ? z0 : (j == 1 ? z1 : (j == 2 ? z2 : z3)), n);
        a0 = (j == 0) ? a : a0;
        a1 = (j == 1) ? a : a1;
        a2 = (j == 2) ? a : a2;
        a3 = (j == 3) ? a : a3;
        pending &= pending - 1u;
    } while (pending != 0u);
    SAO_STORE_OUTPUT(x0, a0);
    if (x1.x < size.x)
        SAO_STORE_OUTPUT(x1, a1);
    if (x2.y < size.y)
        SAO_STORE_OUTPUT(x2, a2);
    if (all(lessThan(x3, size)))
        SAO_STORE_OUTPUT(x3, a3);
}
#pragma sao end
