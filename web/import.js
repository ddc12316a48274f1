// "Import design…": a designer's file (OpticStudio .zmx, CODE V .seq, Zemax Grid Sag .DAT),
// with the Grid Sag .DAT a .zmx names chosen together with it, read by the wasm core
// (`design_surfaces`, `import_design` in web/src/design.rs, the same code as `spiralcam
// import`). A dialog lists the file's surfaces and asks which to cut, optic or mould, and the
// part's diameter when the file gives none; the job made fills the form, and what was read
// (types, coefficients, units, semi-diameter, the side cut) is shown above the form to compare
// with the prescription report. Nothing is read here in JavaScript but the files' bytes.

import { design_surfaces, import_design } from '../pkg/spiralcam_web.js';

const $ = (id) => document.getElementById(id);

/** The design among the chosen files: a .zmx or .seq, else the first (a .DAT alone). */
function designOf(files) {
  return files.find((f) => /\.(zmx|seq)$/i.test(f.name)) || files[0];
}

/** The surface offered first: the file's default, else the first readable one between object
 * and image. */
function firstSurface(info) {
  if (info.default_surface !== null) return info.default_surface;
  const s = info.surfaces.find((x) => x.role === 'surface' && x.readable) || info.surfaces[0];
  return s ? s.number : 0;
}

/** Binds the "Import design…" control: `fill(job, listing)` receives the job made. */
export function bindImport(fill) {
  const dialog = $('import-dialog');
  const surface = $('import-surface');
  const cut = $('import-cut');
  const diameter = $('import-diameter');
  const error = $('import-error');
  let chosen = null;

  /** The needs of the surface selected: the piece for a refracting one, its data files. */
  const describe = () => {
    const s = chosen.info.surfaces.find((x) => String(x.number) === surface.value);
    const missing = (s?.data_files || []).filter((p) => {
      const base = p.split(/[\\/]/).pop().toLowerCase();
      return !chosen.names.some((n) => n.toLowerCase() === base);
    });
    cut.options[0].textContent = s?.mirror ? 'the optic (a mirror\'s default)' : 'choose: the surface refracts';
    $('import-needs').textContent = missing.length
      ? `This surface reads ${missing.join(', ')}: choose it together with ${chosen.name}.`
      : '';
    error.textContent = '';
  };

  $('import-design').addEventListener('change', async (e) => {
    const files = [...e.target.files];
    e.target.value = '';
    if (!files.length) return;
    const design = designOf(files);
    const others = files.filter((f) => f !== design);
    try {
      const bytes = new Uint8Array(await design.arrayBuffer());
      const info = JSON.parse(design_surfaces(design.name, bytes));
      chosen = { name: design.name, bytes, info, names: others.map((f) => f.name), texts: await Promise.all(others.map((f) => f.text())) };
    } catch (err) {
      chosen = null;
      $('import-file').textContent = design.name;
      $('import-about').textContent = '';
      surface.replaceChildren();
      error.textContent = err.message;
      dialog.showModal();
      return;
    }
    const { info } = chosen;
    $('import-file').textContent = info.file;
    $('import-about').textContent = [`${info.format}, ${info.encoding}, lens unit ${info.unit}`, ...info.notes].join('\n');
    surface.replaceChildren(...info.surfaces.map((s) => Object.assign(document.createElement('option'), { value: String(s.number), textContent: s.summary })));
    surface.value = String(firstSurface(info));
    cut.value = '';
    diameter.value = '';
    describe();
    dialog.showModal();
  });

  surface.addEventListener('change', describe);
  $('import-cancel').addEventListener('click', () => dialog.close());
  $('import-fill').addEventListener('click', () => {
    if (!chosen) return;
    const d = diameter.value.trim();
    try {
      const made = JSON.parse(import_design(chosen.name, chosen.bytes, Number(surface.value), cut.value,
        d === '' ? undefined : Number(d), chosen.names, chosen.texts));
      dialog.close();
      fill(made.job, made.listing);
    } catch (err) {
      error.textContent = err.message;
    }
  });
}
