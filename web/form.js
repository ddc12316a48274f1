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
      { key: 'base', kind: 'base' },
      { key: 'conic', label: 'Conic k', unit: '', hint: '0 sphere, −1 paraboloid', optionalNumber: true },
      { key: 'coefficients', kind: 'coefficients' },
    ],
  },
  xy_polynomial: {
    label: 'XY polynomial',
    fields: [
      { key: 'base', kind: 'nested_base' },
      { key: 'norm_radius_mm', label: 'Normalisation radius N', unit: 'mm', hint: '> 0' },
      { key: 'terms', kind: 'terms' },
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
  paper004: {
    label: 'Paper 004 Table 1 lens array (Ø10 mm, R 2.84 mm, 1 mm pitch, −44.4 µm)',
    apply: (job) => {
      job.part.diameter_mm = 10;
      job.surface = { type: 'lens_array', lens_radius_mm: 2.84, aperture_mm: 1, pitch_mm: 1, grid: 'rectangular', form: 'concave' };
    },
  },
};

/** Defaults for a family the user switches to. */
const FAMILY_DEFAULTS = {
  lens_array: { lens_radius_mm: 2.84, aperture_mm: 1, pitch_mm: 1, grid: 'rectangular', form: 'concave' },
  asphere: { radius_mm: 40, conic: 0 },
  xy_polynomial: { base: { radius_mm: 80 }, norm_radius_mm: 5, terms: [{ x: 2, y: 1, coefficient_mm: 0.001 }] },
  sinusoid: { amplitude_mm: 0.002, wavelength_x_mm: 1, wavelength_y_mm: 1, phase_x_deg: 0, phase_y_deg: 0 },
};

/** The fixed sections: [section title, [field descriptions]]. */
const SECTIONS = [
  ['Job', [{ path: 'name', label: 'Name', text: true, hint: 'letters, digits, - _ .' }]],
  ['Part', [{ path: 'part.diameter_mm', label: 'Diameter', unit: 'mm', hint: '> 0' }]],
  ['Tool', [
    { path: 'tool.nose_radius_mm', label: 'Nose radius r', unit: 'mm', hint: '≥ 0' },
    { path: 'tool.included_angle_deg', label: 'Included angle', unit: '°', hint: '(0, 180]' },
  ]],
  ['Machine', [{ path: 'machine.spindle_rpm', label: 'Spindle speed', unit: 'rpm', hint: '> 0' }]],
  ['Strategy', [
    { path: 'strategy.feed_mm_per_rev', label: 'Feed f', unit: 'mm/rev', hint: '> 0' },
    { path: 'strategy.sampling.type', label: 'Sampling', options: ['constant_angle', 'constant_arc'] },
    { path: 'strategy.sampling.points_per_rev', label: 'Points per revolution', unit: '', hint: '3 … 1 000 000', when: 'constant_angle' },
    { path: 'strategy.sampling.arc_length_mm', label: 'Arc length ΔS', unit: 'mm', hint: '> 0', when: 'constant_arc' },
    { path: 'strategy.sampling.max_angle_step_deg', label: 'Largest angle step', unit: '°', hint: '(0, 90]', when: 'constant_arc' },
    { path: 'strategy.direction', label: 'Direction of θ', options: ['ccw', 'cw'] },
    { path: 'strategy.start_angle_deg', label: 'Start angle', unit: '°' },
    { path: 'strategy.outer_radius_mm', label: 'Outer radius', unit: 'mm', hint: 'blank: part radius', optional: true },
  ]],
  ['NC output', [
    { path: 'output.dialect', label: 'Dialect', options: ['iso', 'moore', 'precitech'] },
    { path: 'output.decimals_xz', label: 'Decimals X, Z', unit: '', hint: '0 … 9 (6 = 1 nm)' },
    { path: 'output.decimals_c', label: 'Decimals C', unit: '', hint: '0 … 9' },
    { path: 'output.x_sign', label: 'Sign of X', options: ['', '1', '-1'], optionLabels: ['dialect default', '+1', '−1'], optional: true, numeric: true },
    { path: 'output.z_sign', label: 'Sign of Z', options: ['', '1', '-1'], optionLabels: ['dialect default', '+1', '−1'], optional: true, numeric: true },
    { path: 'output.c_sign', label: 'Direction of C', options: ['', '1', '-1'], optionLabels: ['dialect default', '+1', '−1'], optional: true, numeric: true },
    { path: 'output.wrap_c', label: 'Wrap C to [0, 360)', options: ['', 'true', 'false'], optionLabels: ['dialect default', 'yes', 'no'], optional: true, boolean: true },
    { path: 'output.feed_mode', label: 'Feed', options: ['inverse_time', 'per_minute'], optionLabels: ['G93 inverse time', 'G94 per minute'] },
    { path: 'output.feed_mm_per_min', label: 'Feed (G94)', unit: 'mm/min', optional: true },
    { path: 'output.plunge_feed_mm_per_min', label: 'Plunge feed', unit: 'mm/min' },
    { path: 'output.clearance_mm', label: 'Clearance', unit: 'mm', hint: '≥ 0' },
  ]],
];

function get(obj, path) {
  return path.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj);
}

function set(obj, path, value) {
  const keys = path.split('.');
  let o = obj;
  for (const k of keys.slice(0, -1)) {
    if (o[k] == null || typeof o[k] !== 'object') o[k] = {};
    o = o[k];
  }
  const last = keys[keys.length - 1];
  if (value === undefined) delete o[last];
  else o[last] = value;
}

/** A number from the text typed; blank gives NaN so the core names the field. */
function number(text) {
  return text.trim() === '' ? NaN : Number(text);
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

function select(options, labels) {
  const s = el('select');
  options.forEach((o, i) => s.append(el('option', { value: o }, labels ? labels[i] : o.replaceAll('_', ' '))));
  return s;
}

/** The job form inside `root`; `onChange()` is called after every edit. */
export class JobForm {
  constructor(root, onChange) {
    this.root = root;
    this.onChange = onChange;
    this.job = null;
    root.addEventListener('input', (e) => this.edited(e));
    root.addEventListener('change', (e) => this.edited(e));
    root.addEventListener('click', (e) => this.clicked(e));
  }

  /** Shows `job` (a plain object as in the job JSON). */
  show(job) {
    this.job = structuredClone(job);
    this.root.replaceChildren();
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
    const value = get(this.job, f.path);
    let control;
    if (f.options) {
      control = select(f.options, f.optionLabels);
      control.value = value === undefined ? '' : String(value);
    } else {
      control = el('input', { type: 'text', inputMode: f.text ? 'text' : 'decimal', spellcheck: false });
      control.value = value === undefined || value === null ? '' : String(value);
    }
    control.dataset.kind = f.options ? (f.boolean ? 'bool' : f.numeric ? 'sign' : 'choice') : f.text ? 'text' : 'number';
    if (f.optional) control.dataset.optional = '1';
    const r = row(f.path, f.label, control, f.unit, f.hint);
    if (f.when) r.dataset.when = f.when;
    return r;
  }

  surfaceRows() {
    const box = el('div', { class: 'surface-fields' });
    const s = this.job.surface;
    for (const f of SURFACES[s.type].fields) {
      if (f.kind === 'base' || f.kind === 'nested_base') {
        const prefix = f.kind === 'base' ? 'surface' : 'surface.base';
        const base = f.kind === 'base' ? s : s.base;
        const byRadius = base.curvature_per_mm === undefined;
        const which = select(['radius_mm', 'curvature_per_mm'], ['vertex radius R (mm)', 'vertex curvature c (1/mm)']);
        which.value = byRadius ? 'radius_mm' : 'curvature_per_mm';
        which.dataset.role = 'base-kind';
        which.dataset.prefix = prefix;
        const v = el('input', { type: 'text', inputMode: 'decimal' });
        v.value = String(byRadius ? base.radius_mm : base.curvature_per_mm);
        v.dataset.kind = 'base-value';
        v.dataset.prefix = prefix;
        box.append(row(`${prefix}.${which.value}`, f.kind === 'base' ? 'Base' : 'Base asphere', v, '', 'R ≠ 0; c = 0 for a plane'));
        box.lastChild.insertBefore(which, v);
        if (f.kind === 'nested_base') {
          const k = el('input', { type: 'text', inputMode: 'decimal' });
          k.value = base.conic === undefined ? '' : String(base.conic);
          k.dataset.kind = 'number';
          k.dataset.optional = '1';
          box.append(row('surface.base.conic', 'Base conic k', k, ''));
        }
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
      } else {
        const value = s[f.key];
        let control;
        if (f.options) {
          control = select(f.options);
          control.value = value;
          control.dataset.kind = 'choice';
        } else {
          control = el('input', { type: 'text', inputMode: 'decimal' });
          control.value = value === undefined ? '' : String(value);
          control.dataset.kind = 'number';
          if (f.optionalNumber) control.dataset.optional = '1';
        }
        box.append(row(`surface.${f.key}`, f.label, control, f.unit, f.hint));
      }
    }
    return box;
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
    const type = get(this.job, 'strategy.sampling.type');
    for (const r of this.root.querySelectorAll('[data-when]')) r.hidden = r.dataset.when !== type;
  }

  /** Applies one edit to the job and tells the owner. */
  edited(e) {
    const t = e.target;
    if (e.type === 'input' && t.tagName === 'SELECT') return;
    if (t.dataset.role === 'preset') {
      if (!t.value) return;
      PRESETS[t.value].apply(this.job);
      this.show(this.job);
    } else if (t.dataset.role === 'family') {
      this.job.surface = { type: t.value, ...structuredClone(FAMILY_DEFAULTS[t.value]) };
      this.show(this.job);
    } else if (t.dataset.role === 'base-kind') {
      const base = t.dataset.prefix === 'surface' ? this.job.surface : this.job.surface.base;
      const v = base.radius_mm ?? base.curvature_per_mm;
      delete base.radius_mm;
      delete base.curvature_per_mm;
      base[t.value] = v;
      this.show(this.job);
    } else if (t.dataset.kind) {
      this.read(t);
      if (t.dataset.field === 'strategy.sampling.type') {
        this.job.strategy.sampling = t.value === 'constant_angle'
          ? { type: 'constant_angle', points_per_rev: 720 }
          : { type: 'constant_arc', arc_length_mm: 0.02, max_angle_step_deg: 1 };
        this.show(this.job);
      }
    } else {
      return;
    }
    this.onChange();
  }

  /** Reads one control into the job. */
  read(t) {
    const path = t.dataset.field;
    switch (t.dataset.kind) {
      case 'text': set(this.job, path, t.value); break;
      case 'choice': set(this.job, path, t.value); break;
      case 'sign': set(this.job, path, t.value === '' ? undefined : Number(t.value)); break;
      case 'bool': set(this.job, path, t.value === '' ? undefined : t.value === 'true'); break;
      case 'number': set(this.job, path, t.dataset.optional && t.value.trim() === '' ? undefined : number(t.value)); break;
      case 'base-value': {
        const base = t.dataset.prefix === 'surface' ? this.job.surface : this.job.surface.base;
        const key = base.curvature_per_mm === undefined ? 'radius_mm' : 'curvature_per_mm';
        base[key] = number(t.value);
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
      case 'term': {
        const term = this.job.surface.terms[Number(t.dataset.index)];
        term[t.dataset.key] = number(t.value);
        break;
      }
      default: break;
    }
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
    this.onChange();
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
      || candidates.find((c) => path.startsWith(`${c.dataset.field}.`) || c.dataset.field.startsWith(`${path}.`) || c.dataset.field.startsWith(`${path}[`));
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
