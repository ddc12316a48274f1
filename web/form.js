// The job form: a schema of every job field (label, unit, range hint), the form built from it,
// and the two conversions job → form and form → job. Field elements carry `data-field` with the
// job path the core uses in its error messages (e.g. "tool.nose_radius_mm"), so an error can be
// shown beside its field. Values are read with Number() from the text the user typed, which
// gives the same doubles as the command line reading the same digits from a JSON file.

/** Surface families: the job's `surface.type` and its fields. */
export const SURFACES = {
  lens_array: {
    label: 'Microlens array',
    fields: [
      { key: 'lens_radius_mm', label: 'Lenslet radius R', unit: 'mm', hint: '≥ aperture/2' },
      { key: 'aperture_mm', label: 'Clear aperture', unit: 'mm', hint: '≤ pitch' },
      { key: 'pitch_mm', label: 'Pitch', unit: 'mm', hint: '> 0' },
      { key: 'grid', label: 'Grid', options: ['rectangular', 'hexagonal'] },
      { key: 'form', label: 'Form', options: ['concave', 'convex'] },
    ],
  },
  asphere: {
    label: 'Even asphere',
    fields: [
      { kind: 'radius', label: 'Vertex' },
      { key: 'conic', label: 'Conic k', unit: '', hint: '0 sphere, −1 paraboloid', optionalNumber: true },
      { key: 'coefficients', kind: 'coefficients' },
    ],
  },
  odd_asphere: {
    label: 'Odd asphere (β1·r + β2·r² + …)',
    fields: [
      { kind: 'radius', label: 'Vertex' },
      { key: 'conic', label: 'Conic k', unit: '', hint: '0 sphere, −1 paraboloid', optionalNumber: true },
      { key: 'coefficients', kind: 'list', label: 'Coefficients β1, β2, … (mm^(1−n))', hint: 'β1 multiplies r¹ (OpticStudio Odd Asphere order); at most 30' },
    ],
  },
  zoned_asphere: {
    label: 'Zoned asphere (concentric zones)',
    fields: [
      { key: 'zones', kind: 'json', rows: 12, label: 'Zones (JSON list, from the axis out)', hint: '[{"outer_radius_mm", "radius_mm" or "curvature_per_mm", "conic", "coefficients" [A4 …], "offset_mm"}]; the last zone may omit its outer radius' },
    ],
  },
  xy_polynomial: {
    label: 'XY polynomial',
    fields: [
      { kind: 'radius', object: 'base', label: 'Base vertex' },
      { key: 'base.conic', label: 'Base conic k', unit: '', optionalNumber: true },
      { key: 'norm_radius_mm', label: 'Normalisation radius N', unit: 'mm', hint: '> 0' },
      { key: 'terms', kind: 'terms' },
    ],
  },
  zernike: {
    label: 'Zernike (Standard or Fringe)',
    fields: [
      { key: 'convention', label: 'Convention', options: ['standard', 'fringe'], optionLabels: ['Standard (Noll, RMS-normalised, ≤ 231)', 'Fringe (Arizona, ≤ 37)'] },
      { kind: 'radius', object: 'base', label: 'Base vertex' },
      { key: 'base.conic', label: 'Base conic k', unit: '', optionalNumber: true },
      { key: 'norm_radius_mm', label: 'Normalisation radius N', unit: 'mm', hint: '> 0' },
      { key: 'coefficients_mm', kind: 'list', label: 'Coefficients c₁, c₂, … (mm)', hint: 'in index order of the convention; see crate/docs/zernike.md' },
    ],
  },
  q_bfs: {
    label: 'Q-bfs asphere (Forbes 2007)',
    fields: [
      { kind: 'radius', label: 'Best-fit sphere' },
      { key: 'norm_radius_mm', label: 'Normalisation radius N', unit: 'mm', hint: '> 0' },
      { key: 'coefficients_mm', kind: 'list', label: 'Coefficients a0, a1, … (mm)', hint: 'at most 31' },
    ],
  },
  q_con: {
    label: 'Q-con asphere (Forbes 2007)',
    fields: [
      { kind: 'radius', label: 'Vertex' },
      { key: 'conic', label: 'Conic k', unit: '', optionalNumber: true },
      { key: 'norm_radius_mm', label: 'Normalisation radius N', unit: 'mm', hint: '> 0' },
      { key: 'coefficients_mm', kind: 'list', label: 'Coefficients a0, a1, … (mm)', hint: 'at most 31' },
    ],
  },
  q_2d: {
    label: 'Q-2D freeform (Forbes 2012)',
    fields: [
      { kind: 'radius', label: 'Best-fit sphere' },
      { key: 'norm_radius_mm', label: 'Normalisation radius N', unit: 'mm', hint: '> 0' },
      { key: 'terms', kind: 'json', rows: 8, label: 'Terms (JSON list)', hint: '[{"n", "m", "a_mm" (cos mθ), "b_mm" (sin mθ)}], n, m ≤ 30; m = 0: the Q-bfs part' },
    ],
  },
  chebyshev: {
    label: 'Chebyshev polynomial',
    fields: [
      { kind: 'radius', object: 'base', label: 'Base vertex' },
      { key: 'base.conic', label: 'Base conic k', unit: '', optionalNumber: true },
      { key: 'half_width_x_mm', label: 'Half-width X0', unit: 'mm', hint: '> 0; blank: the part radius', optionalNumber: true },
      { key: 'half_width_y_mm', label: 'Half-width Y0', unit: 'mm', hint: '> 0; blank: the part radius', optionalNumber: true },
      { key: 'terms', kind: 'json', rows: 8, label: 'Terms (JSON list)', hint: '[{"x": i, "y": j, "coefficient_mm": c}]: c·Ti(x/X0)·Tj(y/Y0), i, j ≤ 20' },
    ],
  },
  biconic: {
    label: 'Biconic',
    fields: [
      { kind: 'radius', suffix: '_x', label: 'X section' },
      { key: 'conic_x', label: 'Conic kx', unit: '', optionalNumber: true },
      { kind: 'radius', suffix: '_y', label: 'Y section' },
      { key: 'conic_y', label: 'Conic ky', unit: '', optionalNumber: true },
    ],
  },
  toroid: {
    label: 'Toroid',
    fields: [
      { kind: 'radius', suffix: '_x', label: 'Rotation (X)' },
      { kind: 'radius', suffix: '_y', label: 'Profile (Y)' },
      { key: 'conic_y', label: 'Profile conic ky', unit: '', optionalNumber: true },
      { key: 'profile_coefficients', kind: 'list', label: 'Profile terms α1, α2, … on y², y⁴, … (mm^(1−2i))', hint: 'OpticStudio Toroidal parameters 2–8; at most 10; blank: none' },
    ],
  },
  off_axis_conic: {
    label: 'Off-axis conic segment',
    fields: [
      { kind: 'radius', object: 'parent', label: 'Parent vertex' },
      { key: 'parent.conic', label: 'Parent conic k', unit: '', optionalNumber: true },
      { key: 'off_axis_distance_mm', label: 'Off-axis distance d', unit: 'mm', hint: '≥ 0' },
      { key: 'clocking_deg', label: 'Clocking α', unit: '°' },
      { key: 'remove_tilt', label: 'Remove tilt', options: ['false', 'true'], optionLabels: ['no', 'yes'], boolean: true },
    ],
  },
  tilted_flat: {
    label: 'Tilted flat',
    fields: [
      { key: 'tilt_deg', label: 'Tilt τ', unit: '°', hint: '|τ| < 90' },
      { key: 'azimuth_deg', label: 'Azimuth β', unit: '°', hint: 'direction of steepest ascent from +X' },
    ],
  },
  pal: {
    label: 'Progressive addition lens',
    fields: [
      { key: 'far_power_d', label: 'Far power', unit: 'D' },
      { key: 'addition_d', label: 'Addition', unit: 'D' },
      { key: 'corridor_length_mm', label: 'Corridor length h', unit: 'mm' },
      { key: 'far_point_mm', label: 'Far point L', unit: 'mm', hint: 'F at x = −L' },
      { key: 'far_order', label: 'Far order m', unit: '', hint: '3 … 8' },
      { key: 'near_order', label: 'Near order l', unit: '', hint: '3 … 8' },
      { key: 'refractive_index', label: 'Refractive index n', unit: '' },
      {
        key: 'contours', kind: 'variant', label: 'Contour curves',
        variants: {
          straight_line: { label: 'straight lines', defaults: {} },
          circle: { label: 'circles', defaults: { centre_x_mm: 100 } },
          hyperbola: { label: 'hyperbolas', defaults: { centre_x_mm: -100, asymptote_slope: 1 } },
        },
      },
      { key: 'contours.centre_x_mm', label: 'Contour centre x', unit: 'mm', when: { field: 'contours.type', is: ['circle', 'hyperbola'] } },
      { key: 'contours.asymptote_slope', label: 'Asymptote slope a', unit: '', when: { field: 'contours.type', is: ['hyperbola'] } },
    ],
  },
  compound_eye: {
    label: 'Compound eye',
    fields: [
      { key: 'base_radius_mm', label: 'Base sphere radius', unit: 'mm', hint: 'negative: dome towards the tool; blank: flat', optionalNumber: true },
      { key: 'element_rings', label: 'Element rings', unit: '', hint: '0 → 1 element, 1 → 7, 2 → 19' },
      { key: 'element_pitch_mm', label: 'Element pitch', unit: 'mm' },
      { key: 'element_radius_mm', label: 'Element radius', unit: 'mm' },
      { key: 'element_height_mm', label: 'Element height', unit: 'mm', hint: 'along the base normal' },
      { key: 'lenslet_rows', kind: 'list', label: 'Lenslets per row', hint: 'e.g. 3, 4, 3, 4, 3 = 17 lenslets' },
      { key: 'lenslet_pitch_mm', label: 'Lenslet pitch', unit: 'mm' },
      { key: 'lenslet_radius_mm', label: 'Lenslet radius', unit: 'mm' },
      { key: 'lenslet_height_mm', label: 'Lenslet height', unit: 'mm', hint: 'along the element normal' },
    ],
  },
  nurbs: {
    label: 'NURBS (control net)',
    fields: [
      { key: 'degree_u', label: 'Degree in u', unit: '', hint: '1 … 15' },
      { key: 'degree_v', label: 'Degree in v', unit: '', hint: '1 … 15' },
      { key: 'knots_u', kind: 'list', label: 'Knots u', hint: 'n + p + 1 non-decreasing numbers' },
      { key: 'knots_v', kind: 'list', label: 'Knots v', hint: 'm + q + 1 non-decreasing numbers' },
      { key: 'control_points', kind: 'json', rows: 10, label: 'Control points (JSON rows of [x, y, z], mm)' },
      { key: 'weights', kind: 'json', rows: 3, label: 'Weights (JSON rows; null = all 1)' },
    ],
  },
  step_face: {
    label: 'STEP face (B-spline/NURBS)',
    fields: [
      { key: 'file', kind: 'file', accept: '.step,.stp', label: 'STEP file' },
      { key: 'face', kind: 'json', rows: 1, label: 'Face (index or "#id"; null = the only one)' },
      { key: 'units', label: 'Length unit', options: ['file', 'mm', 'um', 'm', 'inch'], optionLabels: ['as the file states', 'mm', 'µm', 'm', 'inch'] },
      { key: 'flip', label: 'Flip (axis along −Z)', options: ['false', 'true'], optionLabels: ['no', 'yes'], boolean: true },
      { key: 'z_offset_mm', label: 'Z offset', unit: 'mm', optionalNumber: true },
    ],
  },
  scattered: {
    label: 'Scattered data (RBF, paper 004)',
    fields: [
      { key: 'data', kind: 'file', accept: '.csv,.txt,.grid', label: 'Data file', hint: 'CSV x, y, z (mm) or a height grid' },
      { key: 'method', label: 'Interpolator', options: ['rbf', 'shepard', 'four_point_mean', 'hermite'], optionLabels: ['RBF (eqs 4–6)', 'Shepard (IDW)', 'four-point mean', 'Hermite (grid only)'] },
      { key: 'neighbours', label: 'Neighbours n', unit: '', hint: 'blank: 8 (rbf 4…16, shepard 2…16)', optionalNumber: true, when: { field: 'method', is: ['rbf', 'shepard'] } },
      { key: 'rbf_distance', label: 'RBF distance', options: ['', 'l1', 'euclidean'], optionLabels: ['by data (grid: L1, else Euclidean)', 'L1 (eq 4; grid data only)', 'Euclidean'], optional: true, when: { field: 'method', is: ['rbf'] } },
      { key: 'rbf_polynomial', label: 'RBF polynomial term', options: ['linear', 'constant', 'none'], optionLabels: ['linear (reproduces planes)', 'constant', 'none (eq 6 as printed)'], when: { field: 'method', is: ['rbf'] } },
      { key: 'rbf_c', label: 'RBF constant c', unit: '', hint: 'blank: default', optionalNumber: true, when: { field: 'method', is: ['rbf'] } },
      { key: 'rbf_scale', label: 'RBF scale', unit: '× spacing', hint: '0.01 … 100, blank: 1', optionalNumber: true, when: { field: 'method', is: ['rbf'] } },
    ],
  },
  grid_sag: {
    label: 'Grid Sag (Zemax .DAT)',
    fields: [
      { key: 'data', kind: 'file', accept: '.dat,.DAT,.txt', label: 'Grid Sag file', hint: 'nx ny delx dely unitflag xdec ydec, then z dz/dx dz/dy d2z/dxdy [nodata] per point' },
      { key: 'base', kind: 'json', rows: 2, label: 'Base asphere (JSON; null = plane)', hint: '{"radius_mm": R, "conic": k, "coefficients": [A4, …]}' },
    ],
  },
  composite: {
    label: 'Composite (base + terms)',
    fields: [
      { key: 'base', kind: 'json', rows: 5, label: 'Base surface (JSON)', hint: 'any family, as in the job format' },
      { key: 'terms', kind: 'json', rows: 14, label: 'Terms (JSON list)', hint: '[{"surface": {…}, "decenter_x_mm", "decenter_y_mm", "rotation_deg"}]' },
    ],
  },
  sinusoid: {
    label: 'Sinusoidal grid',
    fields: [
      { key: 'amplitude_mm', label: 'Amplitude A', unit: 'mm' },
      { key: 'wavelength_x_mm', label: 'Wavelength λx', unit: 'mm', hint: '> 0' },
      { key: 'wavelength_y_mm', label: 'Wavelength λy', unit: 'mm', hint: '> 0' },
      { key: 'phase_x_deg', label: 'Phase φx', unit: '°' },
      { key: 'phase_y_deg', label: 'Phase φy', unit: '°' },
    ],
  },
};

/** Presets offered above the surface form. */
export const PRESETS = {
  paper000: {
    label: 'Paper 000 multiple compound eye (7 elements × 17 lenslets, Ø10 mm; dimensions ours)',
    apply: (job) => {
      job.name = 'compound-eye-paper000';
      job.part.diameter_mm = 10;
      job.surface = { type: 'compound_eye', ...structuredClone(FAMILY_DEFAULTS.compound_eye) };
      job.tool.nose_radius_mm = 0.05;
      job.strategy.feed_mm_per_rev = 0.005;
      job.strategy.sampling = { type: 'constant_arc', arc_length_mm: 0.0175, max_angle_step_deg: 1 };
    },
  },
  paper003: {
    label: 'Paper 003 Table 1 progressive lens on Ø70 mm (finishing: 180 points/rev, 0.01 mm/rev, r 0.8 mm)',
    apply: (job) => {
      job.name = 'pal-paper003';
      job.machine.spindle_rpm = 60;
      job.part.diameter_mm = 70;
      job.surface = { type: 'pal', ...structuredClone(FAMILY_DEFAULTS.pal) };
      job.tool.nose_radius_mm = 0.8;
      job.strategy.feed_mm_per_rev = 0.01;
      job.strategy.sampling = { type: 'constant_angle', points_per_rev: 180 };
    },
  },
  paper004: {
    label: 'Paper 004 Table 1 lens array (Ø10 mm, R 2.84 mm, 1 mm pitch, −44.4 µm)',
    apply: (job) => {
      job.name = 'lens-array-paper004';
      job.part.diameter_mm = 10;
      job.surface = { type: 'lens_array', lens_radius_mm: 2.84, aperture_mm: 1, pitch_mm: 1, grid: 'rectangular', form: 'concave' };
    },
  },
};

/** Defaults for a family the user switches to. */
const FAMILY_DEFAULTS = {
  lens_array: { lens_radius_mm: 2.84, aperture_mm: 1, pitch_mm: 1, grid: 'rectangular', form: 'concave' },
  asphere: { radius_mm: 40, conic: 0 },
  odd_asphere: { radius_mm: 50, conic: -0.8, coefficients: [0, 0, 2e-5, -1.5e-6, 4e-8] },
  q_bfs: { radius_mm: 40, norm_radius_mm: 5, coefficients_mm: [0.01, -0.002, 0.0008] },
  q_con: { radius_mm: 40, conic: -1, norm_radius_mm: 5, coefficients_mm: [0.005, -0.0015, 0.0005] },
  q_2d: {
    radius_mm: 60, norm_radius_mm: 5,
    terms: [{ n: 0, m: 0, a_mm: 0.003 }, { n: 0, m: 2, a_mm: 0.002 }, { n: 1, m: 1, a_mm: 0.0005, b_mm: -0.0003 }],
  },
  chebyshev: {
    base: { radius_mm: 80 },
    terms: [{ x: 2, y: 0, coefficient_mm: 0.002 }, { x: 0, y: 2, coefficient_mm: -0.0015 }, { x: 1, y: 2, coefficient_mm: 0.0008 }],
  },
  zoned_asphere: {
    zones: [
      { outer_radius_mm: 1, radius_mm: 40, conic: -1 },
      { radius_mm: 45, conic: -1, offset_mm: 0.001388888888889 },
    ],
  },
  xy_polynomial: { base: { radius_mm: 80 }, norm_radius_mm: 5, terms: [{ x: 2, y: 1, coefficient_mm: 0.001 }] },
  sinusoid: { amplitude_mm: 0.002, wavelength_x_mm: 1, wavelength_y_mm: 1, phase_x_deg: 0, phase_y_deg: 0 },
  zernike: { convention: 'standard', base: { radius_mm: 100 }, norm_radius_mm: 5, coefficients_mm: [0, 0, 0, 0, 0.001, 0, 0.0005] },
  biconic: { radius_x_mm: 50, radius_y_mm: 80, conic_x: 0, conic_y: -1 },
  toroid: { radius_x_mm: 50, radius_y_mm: 80, conic_y: 0 },
  off_axis_conic: { parent: { radius_mm: 100, conic: -1 }, off_axis_distance_mm: 15, clocking_deg: 0, remove_tilt: false },
  tilted_flat: { tilt_deg: 0.05, azimuth_deg: 0 },
  pal: {
    far_power_d: 1, addition_d: 2, corridor_length_mm: 30, far_point_mm: 10, far_order: 3, near_order: 3,
    refractive_index: 1.498, contours: { type: 'hyperbola', centre_x_mm: -100, asymptote_slope: 1 },
  },
  compound_eye: {
    base_radius_mm: -40, element_rings: 1, element_pitch_mm: 2.6, element_radius_mm: 8, element_height_mm: 0.1,
    lenslet_rows: [3, 4, 3, 4, 3], lenslet_pitch_mm: 0.45, lenslet_radius_mm: 2, lenslet_height_mm: 0.016,
  },
  nurbs: {
    degree_u: 2, degree_v: 2, knots_u: [0, 0, 0, 1, 1, 1], knots_v: [0, 0, 0, 1, 1, 1],
    control_points: [
      [[-6, -6, 0.36], [-6, 0, 0], [-6, 6, 0.36]],
      [[0, -6, 0], [0, 0, -0.36], [0, 6, 0]],
      [[6, -6, 0.36], [6, 0, 0], [6, 6, 0.36]],
    ],
  },
  step_face: { file: {} },
  scattered: { data: {}, method: 'rbf' },
  grid_sag: { data: {} },
  composite: {
    base: { type: 'asphere', radius_mm: 60 },
    terms: [{
      surface: { type: 'lens_array', lens_radius_mm: 2.84, aperture_mm: 1, pitch_mm: 1, grid: 'hexagonal', form: 'convex' },
      decenter_x_mm: 0.5, decenter_y_mm: 0, rotation_deg: 15,
    }],
  },
};

/** The fixed sections: [section title, [field descriptions]]. */
const SECTIONS = [
  ['Job', [{ path: 'name', label: 'Name', text: true, hint: 'letters, digits, - _ .' }]],
  ['Part', [
    { path: 'part.diameter_mm', label: 'Diameter', unit: 'mm', hint: '> 0' },
    { path: 'part.beyond_edge', label: 'Beyond the edge', options: ['', 'surface'], optionLabels: ['no material (the nose\'s arc is cut at the edge)', 'the design continues'], optional: true, hint: 'what the nose meets beyond part.diameter_mm / 2' },
    { path: 'part.normal_axis_at_mm', label: 'Spindle axis: normal at x, y', unit: 'mm', hint: 'blank: the design\'s Z; "x, y": the part turned about the design\'s normal there (paper 001)', optional: true, list: true },
    {
      path: 'part.cut', role: 'cut', label: 'Cut',
      options: ['', 'optic design', 'optic turned', 'mould design', 'mould turned'],
      optionLabels: ['not stated (the design\'s frame)', 'optic, in the design\'s frame', 'optic, turned 180° about Y', 'mould, in the design\'s frame', 'mould, turned 180° about Y'],
      hint: 'turned: x → −x, z → −z, a rotation (never a mirror), when the tool comes from the design\'s −Z side; "Import design…" sets it',
    },
  ]],
  ['Tool', [
    { path: 'tool.nose_radius_mm', label: 'Nose radius r', unit: 'mm', hint: '≥ 0' },
    { path: 'tool.included_angle_deg', label: 'Included angle', unit: '°', hint: '(0, 180]' },
    { path: 'tool.rake_deg', label: 'Rake angle', unit: '°', hint: '[−80, 80], blank: 0', optional: true },
    { path: 'tool.clearance_deg', label: 'Front clearance', unit: '°', hint: '[0, 80], blank: 10', optional: true },
  ]],
  ['Machine', [
    { path: 'machine.spindle_rpm', label: 'Spindle speed', unit: 'rpm', hint: '> 0' },
    { role: 'machine-preset', label: 'Machine' },
    { path: 'machine.block_rate_hz', label: 'Block rate', unit: 'Hz', hint: 'NC blocks per second the control runs; blank: not checked', optional: true },
    ...slideFields('x_slide', 'X slide'),
    ...slideFields('z_slide', 'Z slide'),
    { path: 'machine.fts', label: 'Fast tool servo', role: 'fts', options: ['', 'set'], optionLabels: ['none', 'fitted (W axis)'] },
    { path: 'machine.fts.stroke_um', label: 'FTS stroke (PV)', unit: 'µm', hint: '> 0: full stroke, peak to valley', whenField: 'machine.fts', when: 'set' },
    { path: 'machine.fts.bandwidth_hz', label: 'FTS bandwidth', unit: 'Hz', hint: '> 0', whenField: 'machine.fts', when: 'set' },
    { path: 'machine.fts.acceleration_m_per_s2', label: 'FTS acceleration', unit: 'm/s²', hint: '> 0', whenField: 'machine.fts', when: 'set' },
  ]],
  ['Strategy', [
    { path: 'strategy.feed_mm_per_rev', label: 'Feed f', unit: 'mm/rev', hint: '> 0' },
    { path: 'strategy.sampling.type', label: 'Sampling', options: ['constant_angle', 'constant_arc', 'hcaa', 'adaptive', 'space_spiral'], optionLabels: ['constant angle', 'constant arc', 'HCAA (paper 000)', 'adaptive per revolution', 'space spiral (paper 001)'] },
    { path: 'strategy.sampling.pv_tolerance_um', label: 'Linearization PV tolerance', unit: 'µm', hint: '> 0', when: 'hcaa adaptive' },
    { path: 'strategy.sampling.points_per_rev', label: 'Points per revolution', unit: '', hint: '3 … 1 000 000', when: 'constant_angle space_spiral' },
    { path: 'strategy.sampling.base_spans', label: 'Base surface spans', unit: '', hint: '1 … 64', when: 'space_spiral' },
    { path: 'strategy.sampling.arc_length_mm', label: 'Arc length ΔS', unit: 'mm', hint: '≥ 1e-6 (1 nm)', when: 'constant_arc' },
    { path: 'strategy.sampling.max_angle_step_deg', label: 'Largest angle step', unit: '°', hint: '0.00036 … 90', when: 'constant_arc' },
    { path: 'strategy.direction', label: 'Direction of θ', options: ['ccw', 'cw'] },
    { path: 'strategy.compensation', label: 'Nose compensation', options: ['one_way', 'two_way'], optionLabels: ['one-way (Z only; X on the spiral)', 'two-way (along the normal; X moves)'] },
    { path: 'strategy.start_angle_deg', label: 'Start angle', unit: '°', hint: '−360 … 360' },
    { path: 'strategy.outer_radius_mm', label: 'Outer radius', unit: 'mm', hint: 'blank: part radius', optional: true },
    { path: 'strategy.overtravel_mm', label: 'Overtravel', unit: 'mm', hint: '≥ 0: the spiral starts this far outside the part; blank: 0', optional: true },
    {
      path: 'strategy.split.type', label: 'Split Z / W', role: 'split', options: ['', 'symmetric', 'low_pass', 'auto'],
      optionLabels: ['none (Z alone)', 'symmetric part on Z (paper 002)', 'low-pass at a cutoff (paper 000)', 'automatic (lowest cutoff the stroke allows)'],
      hint: 'the slide (Z) and the fast tool servo (W) share the path: Z + W = z; needs a fast tool servo',
    },
    { path: 'strategy.split.cutoff_hz', label: 'Cutoff', unit: 'Hz', hint: '> 0: slower to the slide, faster to the servo', whenField: 'strategy.split.type', when: 'low_pass' },
  ]],
  ['NC output', [
    { path: 'output.dialect', label: 'Dialect', options: ['iso', 'moore', 'precitech'] },
    { path: 'output.decimals_xz', label: 'Decimals X, Z', unit: '', hint: '0 … 9 (6 = 1 nm)' },
    { path: 'output.decimals_c', label: 'Decimals C', unit: '', hint: '0 … 9' },
    { path: 'output.x_sign', label: 'Sign of X', options: ['', '1', '-1'], optionLabels: ['dialect default', '+1', '−1'], optional: true, numeric: true },
    { path: 'output.z_sign', label: 'Sign of Z', options: ['', '1', '-1'], optionLabels: ['dialect default', '+1', '−1'], optional: true, numeric: true },
    { path: 'output.c_sign', label: 'Direction of C', options: ['', '1', '-1'], optionLabels: ['dialect default', '+1', '−1'], optional: true, numeric: true },
    { path: 'output.wrap_c', label: 'Wrap C to [0, 360)', options: ['', 'true', 'false'], optionLabels: ['dialect default', 'yes', 'no'], optional: true, boolean: true },
    { path: 'output.feed_mode', label: 'Feed', options: ['inverse_time', 'block_time_s', 'block_time_min', 'per_minute'], optionLabels: ['G93 F = 1/block time in min (RS274, LinuxCNC)', 'G93 F = block time in s (TwinCAT; lab Moore programs)', 'G93 F = block time in min', 'G94 per minute'], hint: 'what G93\'s F means on your controller: check its manual; the header states the spindle speed either way' },
    { path: 'output.decimals_f', label: 'Decimals F', unit: '', hint: '0 … 9; blank: 3 (6 for block times)', optional: true },
    { path: 'output.max_line_chars', label: 'Longest line', unit: 'chars', hint: '≥ 40; blank: the dialect\'s (ISO 252, Moore and Precitech 128)', optional: true },
    { path: 'output.feed_mm_per_min', label: 'Feed (G94)', unit: 'mm/min', optional: true },
    { path: 'output.plunge_feed_mm_per_min', label: 'Plunge feed', unit: 'mm/min' },
    { path: 'output.clearance_mm', label: 'Clearance', unit: 'mm', hint: '≥ 0' },
    {
      path: 'output.fts_word', label: 'Servo word', options: ['', 'W', 'U', 'V', 'A', 'B', 'Y'], optionLabels: ['dialect default (ISO Y, others W)', 'W', 'U', 'V', 'A', 'B', 'Y'],
      optional: true, hint: 'the fast tool servo\'s word in split programs', whenField: 'strategy.split.type', when: 'symmetric low_pass auto',
    },
    { path: 'output.fts_grid.tolerance_um', label: 'FTS grid tolerance', unit: 'µm', optional: true, hint: 'largest bilinear error of the PMAC table against the planned W; blank: 0.05; set it to see the grid in the report', whenField: 'strategy.split.type', when: 'symmetric low_pass auto' },
  ]],
  ['Program', [
    { path: 'program', label: 'Program', role: 'program', options: ['', 'set'], optionLabels: ['one spiral', 'set-up, passes, loop, child programs'], hint: 'the program an operator runs as written (crate/docs/job-format.md, "The program section")' },
    ...[
      { path: 'program.work_offset', label: 'Work offset', options: ['', 'G54', 'G55', 'G56', 'G57', 'G58', 'G59'], optionLabels: ['none', 'G54', 'G55', 'G56', 'G57', 'G58', 'G59'], optional: true },
      { path: 'program.tool', label: 'Tool word', text: true, optional: true, hint: 'T and 1 to 8 digits, e.g. T0303; blank: none' },
      { path: 'program.c_axis_on', label: 'C-axis mode on', text: true, optional: true, hint: 'an M word, e.g. M26.1; blank: none' },
      { path: 'program.c_axis_off', label: 'C-axis mode off', text: true, optional: true, hint: 'an M word, e.g. M29; blank: none' },
      { path: 'program.safe_z_mm', label: 'Safe Z', unit: 'mm', optional: true, hint: 'start and end height; blank: the path\'s top + stock + clearance' },
      { path: 'program.retract_height_mm', label: 'Retract height', unit: 'mm', optional: true, hint: 'between passes, in the pass\'s frame; blank: the path\'s top + clearance' },
      { path: 'program.approach', label: 'Approach (JSON list)', json: true, rows: 3, hint: '[{"height_mm": h, "feed_mm_per_min": f}, …]: heights above the first point, decreasing; then the plunge feed' },
      { path: 'program.passes', label: 'Passes (JSON list)', json: true, rows: 4, hint: '[{"count": n, "depth_of_cut_um": d, "feed_mm_per_rev"?: f, "spindle_rpm"?: s}, …] cut in order; the last pass cuts the design' },
      { path: 'program.loop', label: 'Passes written', options: ['unrolled', 'controller'], optionLabels: ['every pass written out', 'one body repeated by the controller (G52 shift)'] },
      { path: 'program.max_program_bytes', label: 'Largest program file', unit: 'bytes', optional: true, hint: '≥ 4096; past it, child programs called by the main one (one zip download); blank: one file' },
    ].map((f) => ({ ...f, whenField: 'program', when: 'set' })),
  ]],
];

/** The program section a user switches on: a roughing group and a finishing pass. */
const DEFAULT_PROGRAM = {
  approach: [{ height_mm: 1, feed_mm_per_min: 500 }, { height_mm: 0.1, feed_mm_per_min: 20 }],
  passes: [{ count: 2, depth_of_cut_um: 5 }, { count: 1, depth_of_cut_um: 2 }],
  loop: 'unrolled',
};

/** The three limits of a slide (`machine.<key>`): all three blank = not checked. */
function slideFields(key, name) {
  const group = `machine.${key}`;
  return [
    { path: `${group}.velocity_mm_per_min`, label: `${name} velocity`, unit: 'mm/min', hint: '> 0; all three blank: not checked', group },
    { path: `${group}.acceleration_mm_per_s2`, label: `${name} acceleration`, unit: 'mm/s²', hint: '> 0; all three blank: not checked', group },
    { path: `${group}.bandwidth_hz`, label: `${name} bandwidth`, unit: 'Hz', hint: '> 0; all three blank: not checked', group },
  ];
}

/** What a machine preset sets in `job.machine`. */
const MACHINE_LIMITS = ['block_rate_hz', 'x_slide', 'z_slide', 'fts'];

/** Whether the limits of `machine` are those of `preset` (`null` preset: no limits at all). */
function machineIs(machine, preset) {
  const same = (a, b) => {
    if (a == null || b == null) return a == null && b == null;
    if (typeof a !== 'object' || typeof b !== 'object') return a === b;
    const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
    return [...keys].every((k) => same(a[k], b[k]));
  };
  return MACHINE_LIMITS.every((k) => same(machine[k], preset ? preset[k] : null));
}

/** The servo a user switches on before typing its own limits. */
const DEFAULT_FTS = { stroke_um: 70, bandwidth_hz: 700, acceleration_m_per_s2: 300 };

function get(obj, path) {
  return path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj);
}

function set(obj, path, value) {
  const keys = path.split('.');
  const last = keys[keys.length - 1];
  if (value === undefined) {
    // Removing a field creates no objects on the way to it.
    const parent = keys.length > 1 ? get(obj, keys.slice(0, -1).join('.')) : obj;
    if (parent != null && typeof parent === 'object') delete parent[last];
    return;
  }
  let o = obj;
  for (const k of keys.slice(0, -1)) {
    if (o[k] == null || typeof o[k] !== 'object') o[k] = {};
    o = o[k];
  }
  o[last] = value;
}

/** A number from the text typed; blank gives NaN so the core names the field. */
function number(text) {
  return text.trim() === '' ? NaN : Number(text);
}

/** What is wrong with the text typed in the number field at `path`, before the core sees it:
 * a decimal comma ("use a point: 0.5") or text that is no number; null when it reads (a blank
 * is left to the core, which knows whether the field is optional). */
export function numberProblem(path, text) {
  const t = text.trim();
  if (t === '' || Number.isFinite(Number(t))) return null;
  if (/^[+-]?(\d+,\d*|\d*,\d+)([eE][+-]?\d+)?$/.test(t)) return `${path} = ${t}: a decimal comma; use a point: ${t.replace(',', '.')}`;
  if (Number.isNaN(Number(t))) return `${path} = ${t}: not a number`;
  return null;
}

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('data-')) e.setAttribute(k, v);
    else e[k] = v;
  }
  for (const c of children) e.append(c);
  return e;
}

/** One labelled row: label, control, unit, and an error slot. */
function row(path, label, control, unit, hint) {
  control.dataset.field = path;
  control.id = `f-${path}`;
  const lab = el('label', { htmlFor: control.id }, label);
  const u = el('span', { class: 'unit' }, unit || '');
  const err = el('span', { class: 'error', 'data-error-for': path });
  if (hint) control.title = hint;
  return el('div', { class: 'row' }, lab, control, u, err);
}

/** A row spanning the form's width (text areas, files). */
function wide(r) {
  r.classList.add('wide');
  return r;
}

/** The object a radius row edits (at `object` within the surface, '' for the surface itself)
 * and its two keys, of which it holds exactly one: `radius<suffix>_mm`, `curvature<suffix>_per_mm`. */
function radiusOf(surface, object, suffix) {
  return [object ? get(surface, object) : surface, `radius${suffix}_mm`, `curvature${suffix}_per_mm`];
}

/** The state line of a loaded data file. */
function loaded(name, text) {
  return `${name}: ${(text.length / 1024).toFixed(1)} kB`;
}

function select(options, labels) {
  const s = el('select');
  options.forEach((o, i) => s.append(el('option', { value: o }, labels ? labels[i] : o.replaceAll('_', ' '))));
  return s;
}

/** The job form inside `root`; `onChange()` is called after every edit. `machinePresets`: the
 * core's example machines (`machine_presets()`: key, label, description and the limits). */
export class JobForm {
  constructor(root, onChange, machinePresets = []) {
    this.root = root;
    this.onChange = onChange;
    this.machinePresets = machinePresets;
    this.job = null;
    /** Problems of the text typed in number fields, by job path (`numberProblem`). */
    this.typed = new Map();
    /** The servo's limits last shown, restored when it is switched off and on again. */
    this.lastFts = null;
    root.addEventListener('input', (e) => this.edited(e));
    root.addEventListener('change', (e) => this.edited(e));
    root.addEventListener('click', (e) => this.clicked(e));
  }

  /** Shows `job` (a plain object as in the job JSON). */
  show(job) {
    this.job = structuredClone(job);
    this.typed.clear();
    // A focused field removed here fires its "change" as it goes: that is no edit.
    this.rebuilding = true;
    this.root.replaceChildren();
    this.rebuilding = false;
    const presets = select(['', ...Object.keys(PRESETS)], ['preset…', ...Object.values(PRESETS).map((p) => p.label)]);
    presets.dataset.role = 'preset';
    const family = select(Object.keys(SURFACES), Object.values(SURFACES).map((s) => s.label));
    family.value = this.job.surface.type;
    family.dataset.role = 'family';
    const surface = el('fieldset', {}, el('legend', {}, 'Surface'), el('div', { class: 'row preset' }, presets),
      row('surface.type', 'Family', family, ''), this.surfaceRows());
    for (const [title, fields] of SECTIONS) {
      const fs = el('fieldset', {}, el('legend', {}, title));
      for (const f of fields) fs.append(this.fixedRow(f));
      this.root.append(fs);
      if (title === 'Part') this.root.append(surface);
    }
    this.updateVisibility();
  }

  fixedRow(f) {
    if (f.role === 'machine-preset') return this.machinePresetRow(f);
    const value = get(this.job, f.path);
    let control;
    if (f.role === 'fts' || f.role === 'program') {
      control = select(f.options, f.optionLabels);
      control.value = value ? 'set' : '';
    } else if (f.json) {
      control = el('textarea', { rows: f.rows || 4, spellcheck: false, class: 'json' });
      control.value = JSON.stringify(value ?? [], null, 1).replace(/\n\s*/g, ' ');
    } else if (f.role === 'cut') {
      control = select(f.options, f.optionLabels);
      control.value = value ? `${value.piece} ${value.frame}` : '';
    } else if (f.options) {
      control = select(f.options, f.optionLabels);
      control.value = value === undefined ? '' : String(value);
    } else {
      control = el('input', { type: 'text', inputMode: f.text ? 'text' : 'decimal', spellcheck: false });
      control.value = value === undefined || value === null ? '' : Array.isArray(value) ? value.join(', ') : String(value);
    }
    control.dataset.kind = f.options ? (f.boolean ? 'bool' : f.numeric ? 'sign' : 'choice') : f.json ? 'json' : f.text ? 'text' : f.list ? 'list' : 'number';
    if (f.optional) control.dataset.optional = '1';
    if (f.role) control.dataset.role = f.role;
    if (f.group) control.dataset.group = f.group;
    const r = f.json ? wide(row(f.path, f.label, control, f.unit, f.hint)) : row(f.path, f.label, control, f.unit, f.hint);
    if (f.when) r.dataset.when = f.when;
    if (f.whenField) r.dataset.whenField = f.whenField;
    return r;
  }

  /** The machine preset select: the core's example machines, "none" (no limits) and "custom". */
  machinePresetRow(f) {
    const control = select(['', 'none', ...this.machinePresets.map((p) => p.key)],
      ['custom limits', 'none (no limits checked)', ...this.machinePresets.map((p) => p.label)]);
    this.machinePresets.forEach((p, i) => {
      control.options[i + 2].title = p.description;
    });
    control.dataset.role = 'machine-preset';
    control.id = 'f-machine-preset';
    control.title = 'example machines: orders of magnitude of each class, not any vendor\'s specification';
    const r = el('div', { class: 'row' }, el('label', { htmlFor: control.id }, f.label), control, el('span', { class: 'unit' }, ''));
    this.machinePresetSelect = control;
    this.syncMachinePreset();
    return r;
  }

  /** Shows in the machine preset select which preset the job's limits are, if any. */
  syncMachinePreset() {
    const control = this.machinePresetSelect;
    if (!control) return;
    const m = this.job.machine || {};
    const preset = this.machinePresets.find((p) => machineIs(m, p));
    control.value = preset ? preset.key : machineIs(m, null) ? 'none' : '';
  }

  surfaceRows() {
    const box = el('div', { class: 'surface-fields' });
    const s = this.job.surface;
    for (const f of SURFACES[s.type].fields) {
      if (f.kind === 'radius') {
        box.append(this.radiusRow(f, s));
      } else if (f.kind === 'coefficients') {
        const coeffs = s.coefficients || [];
        const grid = el('div', { class: 'coefficients' });
        for (let i = 0; i < 9; i++) {
          const c = el('input', { type: 'text', inputMode: 'decimal', placeholder: '0' });
          c.value = coeffs[i] === undefined ? '' : String(coeffs[i]);
          c.dataset.kind = 'coefficient';
          c.dataset.index = String(i);
          c.dataset.field = `surface.coefficients[${i}] (A${2 * i + 4})`;
          c.title = `A${2 * i + 4}, mm^${1 - (2 * i + 4)}`;
          grid.append(el('label', {}, `A${2 * i + 4}`, c));
        }
        box.append(el('div', { class: 'row wide' }, el('span', {}, 'Aspheric terms (blank = 0)'), grid,
          el('span', { class: 'error', 'data-error-for': 'surface.coefficients' })));
      } else if (f.kind === 'terms') {
        box.append(this.termsTable(s.terms || []));
      } else if (f.kind === 'list') {
        box.append(this.listRow(f, s));
      } else if (f.kind === 'json') {
        box.append(this.jsonRow(f, s));
      } else if (f.kind === 'file') {
        box.append(this.fileRow(f, s));
      } else if (f.kind === 'variant') {
        box.append(this.variantRow(f, s));
      } else {
        const value = get(s, f.key);
        let control;
        if (f.options) {
          control = select(f.options, f.optionLabels);
          control.value = value === undefined ? String(f.options[0]) : String(value);
          control.dataset.kind = f.boolean ? 'bool' : 'choice';
          if (f.optional) control.dataset.optional = '1';
        } else {
          control = el('input', { type: 'text', inputMode: 'decimal' });
          control.value = value === undefined ? '' : String(value);
          control.dataset.kind = 'number';
          if (f.optionalNumber) control.dataset.optional = '1';
        }
        const r = row(`surface.${f.key}`, f.label, control, f.unit, f.hint);
        if (f.when) {
          r.dataset.whenField = `surface.${f.when.field}`;
          r.dataset.when = f.when.is.join(' ');
        }
        box.append(r);
      }
    }
    return box;
  }

  /** A vertex radius or curvature of the object at `f.object` (see `radiusOf`). */
  radiusRow(f, s) {
    const sfx = f.suffix || '';
    const [obj, rKey, cKey] = radiusOf(s, f.object, sfx);
    const byRadius = obj[cKey] === undefined;
    const which = select([rKey, cKey], ['radius (mm)', 'curvature (1/mm)']);
    which.value = byRadius ? rKey : cKey;
    which.dataset.role = 'radius-kind';
    const v = el('input', { type: 'text', inputMode: 'decimal' });
    v.value = String((byRadius ? obj[rKey] : obj[cKey]) ?? '');
    v.dataset.kind = 'radius-value';
    for (const c of [which, v]) {
      c.dataset.object = f.object || '';
      c.dataset.suffix = sfx;
    }
    const prefix = f.object ? `surface.${f.object}` : 'surface';
    const r = row(`${prefix}.${which.value}`, f.label, v, '', 'R ≠ 0; curvature 0 for flat');
    r.insertBefore(which, v);
    return r;
  }

  /** A choice among object variants (e.g. PAL contour families): switching resets the object. */
  variantRow(f, s) {
    const names = Object.keys(f.variants);
    const control = select(names, names.map((n) => f.variants[n].label));
    control.value = get(s, f.key)?.type ?? names[0];
    control.dataset.role = 'variant';
    control.dataset.key = f.key;
    return row(`surface.${f.key}.type`, f.label, control, '');
  }

  /** A list of numbers typed with commas or spaces, e.g. Zernike coefficients. */
  listRow(f, s) {
    const t = el('textarea', { rows: 3, spellcheck: false });
    t.value = (s[f.key] || []).join(', ');
    t.dataset.kind = 'list';
    return wide(row(`surface.${f.key}`, f.label, t, f.unit, f.hint));
  }

  /** A JSON editor for a structured value (composite terms, a NURBS control net). */
  jsonRow(f, s) {
    const t = el('textarea', { rows: f.rows || 10, spellcheck: false, class: 'json' });
    t.value = JSON.stringify(get(s, f.key) ?? null, null, 2);
    t.dataset.kind = 'json';
    return wide(row(`surface.${f.key}`, f.label, t, '', f.hint));
  }

  /** A data file read in the browser and sent as text (the command line reads paths). */
  fileRow(f, s) {
    const file = s[f.key] || {};
    const input = el('input', { type: 'file', accept: f.accept || '' });
    input.dataset.kind = 'file';
    const what = file.text !== undefined
      ? loaded(file.name || 'loaded', file.text)
      : file.path ? `${file.path} (not loaded: choose the file)` : 'no file';
    const r = wide(row(`surface.${f.key}`, f.label, input, '', f.hint));
    r.append(el('span', { class: 'file-state' }, what));
    return r;
  }

  termsTable(terms) {
    const table = el('table', { class: 'terms' });
    table.append(el('tr', {}, el('th', {}, 'x power'), el('th', {}, 'y power'), el('th', {}, 'coefficient (mm)'), el('th', {}, '')));
    terms.forEach((t, i) => {
      const cell = (key, v) => {
        const inp = el('input', { type: 'text', inputMode: 'decimal' });
        inp.value = String(v);
        inp.dataset.kind = 'term';
        inp.dataset.index = String(i);
        inp.dataset.key = key;
        inp.dataset.field = `surface.terms[${i}]`;
        return el('td', {}, inp);
      };
      const remove = el('button', { type: 'button', textContent: '×', title: 'remove term' });
      remove.dataset.removeTerm = String(i);
      table.append(el('tr', {}, cell('x', t.x), cell('y', t.y), cell('coefficient_mm', t.coefficient_mm), el('td', {}, remove)));
    });
    const add = el('button', { type: 'button', textContent: 'add term' });
    add.dataset.addTerm = '1';
    return el('div', { class: 'row wide' }, el('span', {}, 'Terms cᵢⱼ·(x/N)ⁱ·(y/N)ʲ, i + j ≤ 10'), table, add,
      el('span', { class: 'error', 'data-error-for': 'surface.terms' }));
  }

  updateVisibility() {
    for (const r of this.root.querySelectorAll('[data-when]')) {
      const field = r.dataset.whenField || 'strategy.sampling.type';
      // An option left out of the job has the value its control shows (the default); an object
      // present (the servo) is "set".
      const v = get(this.job, field);
      const value = v !== null && typeof v === 'object' ? 'set' : String(v ?? this.root.querySelector(`[data-field="${field}"]`)?.value);
      r.hidden = !r.dataset.when.split(' ').includes(value);
      // A hidden surface option does not apply to the choice made: it leaves the job.
      if (r.hidden && field.startsWith('surface.')) {
        for (const c of r.querySelectorAll('[data-field]')) {
          set(this.job, c.dataset.field, undefined);
          if (c.tagName === 'INPUT') c.value = '';
          if (c.tagName === 'SELECT') c.selectedIndex = 0;
        }
      }
    }
  }

  /** Applies one edit to the job and tells the owner. */
  edited(e) {
    const t = e.target;
    if (this.rebuilding || !this.root.contains(t)) return;
    if (e.type === 'input' && (t.tagName === 'SELECT' || t.type === 'file')) return;
    if (t.dataset.role === 'preset') {
      if (!t.value) return;
      PRESETS[t.value].apply(this.job);
      this.show(this.job);
    } else if (t.dataset.role === 'family') {
      this.job.surface = { type: t.value, ...structuredClone(FAMILY_DEFAULTS[t.value]) };
      this.show(this.job);
    } else if (t.dataset.role === 'radius-kind') {
      const [obj, rKey, cKey] = radiusOf(this.job.surface, t.dataset.object, t.dataset.suffix);
      const v = obj[rKey] ?? obj[cKey];
      delete obj[rKey];
      delete obj[cKey];
      obj[t.value] = v;
      this.show(this.job);
    } else if (t.dataset.role === 'machine-preset') {
      if (!t.value) return;
      const m = this.job.machine;
      const preset = this.machinePresets.find((p) => p.key === t.value);
      if (m.fts) this.lastFts = m.fts;
      for (const k of MACHINE_LIMITS) {
        if (preset && preset[k] != null) m[k] = structuredClone(preset[k]);
        else delete m[k];
      }
      this.show(this.job);
    } else if (t.dataset.role === 'fts') {
      if (t.value) {
        this.job.machine.fts = structuredClone(this.lastFts || this.machinePresets.find((p) => p.fts)?.fts || DEFAULT_FTS);
      } else {
        if (this.job.machine.fts) this.lastFts = this.job.machine.fts;
        delete this.job.machine.fts;
      }
      this.show(this.job);
    } else if (t.dataset.role === 'program') {
      if (t.value) this.job.program = structuredClone(this.lastProgram || DEFAULT_PROGRAM);
      else {
        if (this.job.program) this.lastProgram = this.job.program;
        delete this.job.program;
      }
      this.show(this.job);
    } else if (t.dataset.role === 'cut') {
      const [piece, frame] = t.value.split(' ');
      set(this.job, 'part.cut', t.value ? { piece, frame } : undefined);
    } else if (t.dataset.role === 'split') {
      const cutoff = this.job.strategy.split?.cutoff_hz ?? this.job.machine.z_slide?.bandwidth_hz ?? 20;
      if (!t.value) delete this.job.strategy.split;
      else this.job.strategy.split = t.value === 'low_pass' ? { type: t.value, cutoff_hz: cutoff } : { type: t.value };
      this.show(this.job);
    } else if (t.dataset.role === 'variant') {
      const f = SURFACES[this.job.surface.type].fields.find((x) => x.key === t.dataset.key);
      set(this.job.surface, t.dataset.key, { type: t.value, ...structuredClone(f.variants[t.value].defaults) });
      this.show(this.job);
    } else if (t.dataset.kind === 'file') {
      const file = t.files[0];
      if (!file) return;
      const key = t.dataset.field.split('.').pop();
      file.text().then((text) => {
        // A file a link or a job named by path keeps its name (reports and headers show it).
        const path = this.job.surface[key]?.path;
        this.job.surface[key] = path ? { path, text } : { text };
        this.show(this.job);
        this.root.querySelector(`[data-field="${t.dataset.field}"]`)?.closest('.row')
          ?.querySelector('.file-state')?.replaceChildren(loaded(file.name, text));
        this.notify();
      });
      return;
    } else if (t.dataset.kind === 'json') {
      try {
        set(this.job, t.dataset.field, JSON.parse(t.value));
        t.classList.remove('invalid');
        t.closest('.row').querySelector('.error').textContent = '';
      } catch (err) {
        t.classList.add('invalid');
        t.closest('.row').querySelector('.error').textContent = `${t.dataset.field}: not JSON: ${err.message}`;
        return;
      }
    } else if (t.dataset.kind) {
      this.read(t);
      if (t.dataset.field === 'strategy.sampling.type') {
        this.job.strategy.sampling = {
          constant_angle: { type: 'constant_angle', points_per_rev: 720 },
          constant_arc: { type: 'constant_arc', arc_length_mm: 0.02, max_angle_step_deg: 1 },
          hcaa: { type: 'hcaa', pv_tolerance_um: 1 },
          adaptive: { type: 'adaptive', pv_tolerance_um: 1 },
          space_spiral: { type: 'space_spiral', points_per_rev: 720, base_spans: 8 },
        }[t.value];
        this.show(this.job);
      }
      this.updateVisibility();
      if (t.dataset.field.startsWith('machine.')) this.syncMachinePreset();
    } else {
      return;
    }
    // A typed field's `change` (on leaving it) repeats what its `input` events did: it re-plans
    // only if the job differs from the one last handed on, or Cancel (which takes the focus
    // from the field it was typed in) would be followed 300 ms later by the same plan again.
    // A list's `change` is its only event and always counts.
    const repeated = e.type === 'change' && t.tagName === 'INPUT' && t.type !== 'file';
    if (repeated && JSON.stringify(this.job) === this.notified) return;
    this.notify();
  }

  /** Hands the edited job on (`onChange`), remembering it. */
  notify() {
    this.notified = JSON.stringify(this.job);
    this.onChange();
  }

  /** Reads one control into the job. */
  read(t) {
    const path = t.dataset.field;
    if (['number', 'radius-value', 'coefficient', 'term'].includes(t.dataset.kind)) {
      const problem = numberProblem(path, t.value);
      if (problem) this.typed.set(path, problem);
      else this.typed.delete(path);
    }
    switch (t.dataset.kind) {
      case 'text': set(this.job, path, t.dataset.optional && t.value.trim() === '' ? undefined : t.value); break;
      case 'choice': set(this.job, path, t.dataset.optional && t.value === '' ? undefined : t.value); break;
      case 'sign': set(this.job, path, t.value === '' ? undefined : Number(t.value)); break;
      case 'bool': set(this.job, path, t.value === '' ? undefined : t.value === 'true'); break;
      case 'number':
        if (t.dataset.group) this.readGroup(t.dataset.group);
        else set(this.job, path, t.dataset.optional && t.value.trim() === '' ? undefined : number(t.value));
        break;
      case 'radius-value': {
        const [obj, rKey, cKey] = radiusOf(this.job.surface, t.dataset.object, t.dataset.suffix);
        obj[obj[cKey] === undefined ? rKey : cKey] = number(t.value);
        break;
      }
      case 'coefficient': {
        const inputs = [...this.root.querySelectorAll('[data-kind="coefficient"]')];
        const values = inputs.map((i) => (i.value.trim() === '' ? 0 : number(i.value)));
        while (values.length && values[values.length - 1] === 0 && inputs[values.length - 1].value.trim() === '') values.pop();
        if (values.length) this.job.surface.coefficients = values;
        else delete this.job.surface.coefficients;
        break;
      }
      case 'list': {
        const items = t.value.split(/[\s,;]+/).filter((v) => v !== '');
        set(this.job, path, t.dataset.optional && !items.length ? undefined : items.map(Number));
        break;
      }
      case 'term': {
        const term = this.job.surface.terms[Number(t.dataset.index)];
        term[t.dataset.key] = number(t.value);
        break;
      }
      default: break;
    }
  }

  /** Reads the fields of an object that is left out when all of them are blank (a slide's
   * limits); one blank among others gives NaN, which the core names. */
  readGroup(group) {
    const inputs = [...this.root.querySelectorAll(`[data-group="${group}"]`)];
    if (inputs.every((i) => i.value.trim() === '')) {
      set(this.job, group, undefined);
      return;
    }
    for (const i of inputs) set(this.job, i.dataset.field, number(i.value));
  }

  /** Handles the add/remove term buttons. */
  clicked(e) {
    const t = e.target;
    if (t.dataset.addTerm) {
      this.job.surface.terms.push({ x: 0, y: 0, coefficient_mm: 0 });
    } else if (t.dataset.removeTerm) {
      this.job.surface.terms.splice(Number(t.dataset.removeTerm), 1);
    } else {
      return;
    }
    this.show(this.job);
    this.notify();
  }

  /** The first problem of the text typed in a number field, or null: the job is not planned
   * while there is one. */
  typedProblem() {
    return this.typed.values().next().value ?? null;
  }

  /** The job as it stands. */
  value() {
    return structuredClone(this.job);
  }

  /** Shows `message` beside the field it names; returns false if no field matched. */
  showError(message) {
    this.clearErrors();
    const path = fieldOf(message);
    if (!path) return false;
    const candidates = [...this.root.querySelectorAll('[data-field]')];
    const control = candidates.find((c) => c.dataset.field === path)
      || candidates.find((c) => path.startsWith(`${c.dataset.field}.`) || path.startsWith(`${c.dataset.field}[`) || c.dataset.field.startsWith(`${path}.`) || c.dataset.field.startsWith(`${path}[`));
    if (!control) return false;
    control.classList.add('invalid');
    const slot = control.closest('.row')?.querySelector('.error');
    if (slot) slot.textContent = message;
    control.closest('fieldset')?.classList.add('has-error');
    return true;
  }

  clearErrors() {
    for (const c of this.root.querySelectorAll('.invalid')) c.classList.remove('invalid');
    for (const c of this.root.querySelectorAll('.error')) c.textContent = '';
    for (const c of this.root.querySelectorAll('.has-error')) c.classList.remove('has-error');
  }
}

/** The job path an error message names: `path = value: …` or `job: path: …`. */
export function fieldOf(message) {
  let m = /^([A-Za-z_][\w.]*(?:\[\d+\][\w.]*)*(?: \(A\d+\))?) = /.exec(message);
  if (m) return m[1];
  m = /^job: ([A-Za-z_][\w.[\]]*): /.exec(message);
  return m ? m[1] : null;
}
