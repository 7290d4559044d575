// Section 1: where the vehicle comes from -- a preset, a saved vehicle (bearer key), the vehicle builder, the
// combination builder (combobuilder.js), or a pasted record -- and what the computations send as `vehicle` (a preset id or a full record).

import * as api from "./api.js";
import { sideView } from "./combination.js";
import * as combo from "./combobuilder.js";
import { $, $$, clear, el, fieldLabel, fmt, grouped, scroller, table } from "./dom.js";
import { value } from "./form.js";

export const state = {
  presets: [], // GET /v1/vehicles
  combinations: [], // GET /v1/combinations (each marked kind: "combination"), when the deployment has it
  details: {}, // GET /v1/combinations/{id}, by id (read once)
  components: null, // GET /v1/components, when the deployment has it
  saved: null, // the loaded saved vehicle (GET /v1/vehicles/{id})
  built: null, // the last POST /v1/vehicles/build answer
  baseSpec: null, // the spec the builder form was filled from (its parts without a box are kept)
};

const RECORD_META = ["id", "title", "source", "models"];

export const source = () => $('input[name="source"]:checked').value;

/** The combination preset the page opens with (a real vehicle, not a validation case of one unit). */
export const DEFAULT_VEHICLE = "tractor-semitrailer-table15";

export function preset(id = $("#preset").value) {
  return state.presets.find((p) => p.id === id) || state.combinations.find((p) => p.id === id) || null;
}

export const isCombination = (entry) => entry?.kind === "combination";

/** A combination preset's full description (GET /v1/combinations/{id}: units, groups, couplings), read once. */
export async function combinationDetail(id) {
  state.details[id] ??= api.get(`/v1/combinations/${encodeURIComponent(id)}`).catch((err) => {
    delete state.details[id];
    throw err;
  });
  return state.details[id];
}

/** What the "record" box and saving send for a preset: its record fields, or {"combination": {...}}. */
export async function presetBody(entry) {
  if (!isCombination(entry)) return presetRecord(entry);
  const { combination } = await combinationDetail(entry.id);
  return { combination };
}

/** The record of a preset list entry (its record fields only). */
export function presetRecord(entry) {
  return Object.fromEntries(Object.entries(entry).filter(([k]) => !RECORD_META.includes(k)));
}

export function showPanel(which) {
  for (const panel of $$("[data-panel]")) panel.hidden = panel.dataset.panel !== which;
  if (which === "saved") $("#catalog-box").open = true; // the key is needed
  const radio = $(`input[name="source"][value="${which}"]`);
  if (radio && !radio.checked) radio.checked = true;
}

/** The picker: the combinations (whole vehicles) first, then the thesis's presets of one unit. */
export function fillPresets(presets, combinations = []) {
  state.presets = presets;
  state.combinations = combinations.map((c) => ({ ...c, kind: "combination" }));
  const select = clear($("#preset"));
  const option = (p) => el("option", { value: p.id }, `${p.title} (${p.id})`);
  if (state.combinations.length) {
    select.append(
      el("optgroup", { label: "Combinations: the whole vehicle in roll" }, state.combinations.map(option)),
      el("optgroup", { label: "Thesis presets: the last unit (2D and 3D models)" }, presets.map(option)),
    );
  } else {
    select.append(...presets.map(option));
  }
  const pending = select.dataset.pending;
  if (pending && !preset(pending)) {
    select.append(el("option", { value: pending }, `${pending} (not a known preset)`));
  }
  if (pending) select.value = pending;
  else if (preset(DEFAULT_VEHICLE)) select.value = DEFAULT_VEHICLE;
  describePreset();
}

export function describePreset() {
  const p = preset();
  const view = $("#preset-view");
  if (view) clear(view);
  if (!p) {
    $("#preset-source").textContent = "";
    return;
  }
  if (!isCombination(p)) {
    $("#preset-source").textContent = `Source: ${p.source}. Models: ${p.models.join(", ")}.`;
    return;
  }
  const coupled = p.roll_coupled_units.map((u) => u.join(" + ")).join("; ");
  $("#preset-source").textContent = `${p.summary} Units: ${p.units.join(", ")}. Roll-coupled units: ${coupled}. Models: ${p.models.join(", ")}.`;
  if (view) {
    combinationDetail(p.id)
      .then((d) => {
        if (preset()?.id !== p.id) return;
        clear(view).append(sideView(d.combination, null), unitsEditor(d.combination));
      })
      .catch(() => undefined);
  }
}

/** Each unit's sprung mass and CG height, editable (the rest of the combination as the preset has it). */
const UNIT_BOXES = [
  { key: "sprung_mass_kg", label: "Sprung mass [kg]", digits: 0 },
  { key: "cg_height_m", label: "CG height [m]", digits: 3 },
];

function unitsEditor(combination) {
  const rows = combination.units.map((u, i) =>
    el(
      "tr",
      {},
      el("td", { class: "text" }, u.id),
      ...UNIT_BOXES.map((b) => {
        const text = String(Number(u[b.key].toFixed(b.digits)));
        const id = `unit-${i}-${b.key}`;
        return el(
          "td",
          {},
          el("label", { for: id, class: "visually-hidden" }, `${u.id}: ${b.label}`),
          el("input", { id, inputmode: "decimal", value: text, "data-initial": text, "data-unit": String(i), "data-key": b.key, "data-field": `vehicle.combination.units.${i}.${b.key}` }),
        );
      }),
    ),
  );
  return el(
    "details",
    { class: "units-editor", id: "units-editor" },
    el("summary", {}, "Each unit: sprung mass and CG height (edit to build your own combination)"),
    el("div", { class: "table-wrap" }, el("table", {}, el("thead", {}, el("tr", {}, el("th", { scope: "col" }, "Unit"), UNIT_BOXES.map((b) => el("th", { scope: "col" }, b.label)))), el("tbody", {}, rows))),
  );
}

/** The preset's combination with the editor's changes, or null when nothing was changed. */
function editedCombination(combination) {
  const boxes = $$("#units-editor input[data-unit]").filter((c) => c.value.trim() !== c.dataset.initial);
  if (!boxes.length) return null;
  const edited = structuredClone(combination);
  for (const c of boxes) edited.units[Number(c.dataset.unit)][c.dataset.key] = value(c) ?? null;
  return edited;
}

/** The model the page picks for the vehicle unless the user chose one: a combination's whole-combination model. */
export function defaultModel() {
  if (source() === "preset") return isCombination(preset()) && preset().models.includes("combination") ? "combination" : null;
  return choosesCombination() ? "combination" : null;
}

/** Whether the saved vehicle loaded for the id typed is a combination (its kind, or its body `{"combination": ...}`). */
function savedCombination() {
  const saved = state.saved;
  if (!saved || saved.id !== $("#saved-id").value.trim()) return false;
  return saved.kind === "combination" || Boolean(saved.vehicle?.combination || saved.vehicle?.combination_spec);
}

/** Whether the vehicle now chosen is a combination (a combination preset, or a pasted {"combination": ...}). */
export function choosesCombination() {
  if (source() === "preset") return isCombination(preset());
  if (source() === "combo") return true;
  if (source() === "saved") return savedCombination(); // a saved combination keeps the combination model
  if (source() === "record") return /^\s*\{\s*"combination"/.test($("#record-json").value);
  return false;
}

/** Models the current vehicle supports (a preset says; a record or a built vehicle: all, the service checks). */
export function supportedModels() {
  return source() === "preset" && preset() ? preset().models : null;
}

// ------------------------------------------------------------------------------------------ builder

function setPath(obj, path, v) {
  const keys = path.split(".");
  let node = obj;
  keys.slice(0, -1).forEach((k, i) => {
    const nextIsIndex = /^\d+$/.test(keys[i + 1]);
    node[k] ??= nextIsIndex ? [] : {};
    node = node[k];
  });
  node[keys.at(-1)] = v;
}

function deletePath(obj, path) {
  const keys = path.split(".");
  const parent = keys.slice(0, -1).reduce((node, k) => (node == null ? undefined : node[k]), obj);
  if (parent && typeof parent === "object") delete parent[keys.at(-1)];
}

/**
 * The builder form as a VehicleSpec object: the spec the form was last filled from (a link, a saved spec) with
 * the form's boxes over it -- an empty box removes its value, parts the form has no box for are kept.
 */
export function specFromForm() {
  const spec = structuredClone(state.baseSpec || {});
  for (const c of $$("[data-spec]", $("#builder"))) {
    const v = value(c);
    if (v === undefined) deletePath(spec, c.dataset.spec);
    else setPath(spec, c.dataset.spec, v);
  }
  // a payload without a mass is no payload (its distribution box always has a value)
  if (Array.isArray(spec.payloads)) spec.payloads = spec.payloads.filter((p) => p && p.mass_kg !== undefined);
  if (Array.isArray(spec.payloads) && !spec.payloads.length) delete spec.payloads;
  for (const part of ["deck", "front_unit"]) if (spec[part] && !Object.keys(spec[part]).length) delete spec[part];
  return spec;
}

/** Fill the builder form from a spec (a link, a saved spec); what the form has no box for is kept aside. */
export function specToForm(spec) {
  state.baseSpec = structuredClone(spec);
  for (const c of $$("[data-spec]", $("#builder"))) {
    const v = c.dataset.spec.split(".").reduce((node, k) => (node == null ? undefined : node[k]), spec);
    if (c.tagName === "SELECT" && (v === undefined || v === null)) continue; // keep the select's default
    if (c.tagName === "SELECT" && !Array.from(c.options).some((o) => o.value === String(v))) {
      c.append(el("option", { value: String(v) }, String(v))); // e.g. a library id before the library is listed
    }
    c.value = v === undefined || v === null ? "" : String(v);
  }
}

/** Each builder box answers for its spec path in problem details (`spec.rear.track_m`). */
export function initBuilder() {
  for (const c of $$("[data-spec]", $("#builder"))) c.dataset.field ??= `spec.${c.dataset.spec}`;
}

/** The library's entries for the builder's tyre and suspension choices (GET /v1/components), and their boxes. */
const LIBRARY = [
  { select: "#b-rear-tyre", list: "tyres", boxes: { loaded_radius_m: "#b-rear-tyre-lr", stiffness_kn_per_m: "#b-rear-tyre-kt" } },
  {
    select: "#b-rear-susp",
    list: "suspensions",
    boxes: { stiffness_kn_per_m: "#b-rear-susp-k", height_m: "#b-rear-susp-h", spring_separation_m: "#b-rear-susp-b" },
  },
];

/**
 * Fill the tyre and suspension choices from the component library. A form not filled from a link starts with
 * each list's first entry (the thesis's tyre and suspension), so the builder's defaults build a vehicle.
 */
export function fillComponents(components) {
  state.components = components;
  for (const { select: id, list } of LIBRARY) {
    const select = $(id);
    for (const entry of components[list]) {
      const known = Array.from(select.options).find((o) => o.value === entry.id);
      if (known) known.textContent = entry.title;
      else select.append(el("option", { value: entry.id }, entry.title));
    }
    if (!state.baseSpec && !select.value && components[list].length) select.value = components[list][0].id;
    select.addEventListener("change", describeComponents);
  }
  describeComponents();
}

/** Under each library choice: its values, with their sources folded; its values as the explicit boxes' placeholders. */
export function describeComponents() {
  for (const { select: id, list, boxes } of LIBRARY) {
    const entry = (state.components?.[list] || []).find((e) => e.id === $(id).value);
    for (const [key, box] of Object.entries(boxes)) $(box).placeholder = entry ? `${entry[key].value} (library)` : "";
    const noteId = `${id.slice(1)}-values`;
    $(`#${noteId}`)?.remove();
    if (!entry) continue;
    const keys = Object.keys(boxes);
    const note = el(
      "div",
      { class: "hint component-values", id: noteId },
      keys.map((k) => `${$(`label[for="${boxes[k].slice(1)}"]`).textContent.replace(/ \[.*\]$/, "")} ${entry[k].value} ${entry[k].unit}`).join(", "),
      el("details", {}, el("summary", {}, "Sources"), el("ul", {}, keys.map((k) => el("li", {}, `${fieldLabel(k)}: ${entry[k].source}`)))),
    );
    $(id).closest(".field").append(note);
  }
}

function derivationTable(built) {
  const rows = Object.entries(built.derivation || {}).map(([field, d]) => ({ field, ...d }));
  return scroller(
    "How each record field was obtained",
    table(
      [
        { key: "field", label: "Record field", format: (v) => fieldLabel(v) },
        { key: "value", label: "Value", format: (v) => (typeof v === "number" ? String(Number(v.toPrecision(6))) : v ?? "-") },
        { key: "unit", label: "Unit", text: true },
        { key: "method", label: "Method", text: true },
        { key: "explanation", label: "How", text: true },
        { key: "source", label: "Source", text: true },
      ],
      rows,
    ),
    true,
  );
}

export function showBuilt(built) {
  const box = clear($("#build-result"));
  box.append(
    el(
      "p",
      {},
      `Built: W = ${fmt(built.vehicle.weight_kn, 2)} kN`,
      built.gross_mass_kg !== undefined ? ` (gross ${grouped(built.gross_mass_kg, 0)} kg)` : "",
      built.group_loads_kg ? `; static group loads ${Object.entries(built.group_loads_kg).map(([k, v]) => `${k} ${grouped(v, 0)} kg`).join(", ")}` : "",
      ".",
    ),
    el("div", { class: "derivation" }, derivationTable(built)),
    ...(built.notes || []).map((n) => el("p", { class: "hint" }, n)),
  );
}

/** POST /v1/vehicles/build -> its answer (vehicle record, derivation, masses, notes) and the spec built. */
export async function build(spec) {
  const built = await api.post("/v1/vehicles/build", { spec });
  state.built = { ...built, spec };
  return state.built;
}

// ------------------------------------------------------------------------------------------ saved vehicles

/** The bearer key typed on the page (a page-local refusal at its box when there is none). */
export function apiKey() {
  const key = $("#api-key").value.trim();
  if (!key) {
    $("#catalog-box").open = true;
    throw Object.assign(new Error("enter the bearer key of your saved vehicles"), { control: $("#api-key") });
  }
  return key;
}

export async function loadSaved() {
  const id = $("#saved-id").value.trim();
  const saved = await api.get(`/v1/vehicles/${encodeURIComponent(id)}`, { key: apiKey() });
  state.saved = saved;
  $("#saved-info").textContent = `${saved.title} (${saved.id}, ${saved.kind}, version ${saved.version}).`;
  return saved;
}

export async function listSaved() {
  const page = await api.get("/v1/vehicles/saved?limit=200", { key: apiKey() });
  const select = clear($("#saved-choice"));
  select.append(el("option", { value: "" }, page.items.length ? "(choose)" : "(none saved under this key)"));
  for (const item of page.items) select.append(el("option", { value: item.id }, `${item.title} (${item.id})`));
  $("#saved-choice-field").hidden = false;
  return page;
}

// ------------------------------------------------------------------------------------------ the reference

/** Turn a `{"spec": ...}` or a record into what computations take (a built spec becomes its record). */
async function resolveBody(body, label) {
  if (body && typeof body === "object" && "spec" in body) {
    if (!(await api.has("post", "/v1/vehicles/build"))) {
      throw new Error("this deployment has no vehicle builder (POST /v1/vehicles/build) to turn the spec into a record");
    }
    const built = await build(body.spec);
    return { ref: built.vehicle, label, built };
  }
  return { ref: body, label };
}

/**
 * The vehicle for the computations: {ref, label, params} where ref is a preset id or a full record and params
 * the URL parameters that reproduce it. A problem local to the page is thrown with `control` set.
 */
export async function current() {
  const which = source();
  if (which === "preset") {
    const p = preset();
    if (!p) {
      const id = $("#preset").value; // an id from the link that is no preset: the service says which exist
      return { ref: id, label: id, record: null, params: { vehicle: id } };
    }
    if (isCombination(p)) {
      const detail = await combinationDetail(p.id);
      const edited = editedCombination(detail.combination);
      if (edited) {
        const body = { combination: { ...edited, title: `${p.title}, edited` } };
        return { ref: body, label: `${p.title} (${p.id}), units edited`, record: null, body, combination: edited, params: { record: JSON.stringify(body) } };
      }
      const body = { combination: detail.combination };
      return { ref: p.id, label: `${p.title} (${p.id})`, record: null, body, combination: detail.combination, params: { vehicle: p.id } };
    }
    return { ref: p.id, label: `${p.title} (${p.id})`, record: presetRecord(p), params: { vehicle: p.id } };
  }
  if (which === "saved") {
    const id = $("#saved-id").value.trim();
    if (!state.saved || state.saved.id !== id) await loadSaved();
    const saved = state.saved;
    const label = `${saved.title} (${saved.id})`;
    if (saved.vehicle?.combination) {
      // its body is sent as it was read (no key needed for each computation); the combination is drawn and printed
      return { ref: saved.vehicle, label, record: null, body: saved.vehicle, combination: saved.vehicle.combination, params: { vehicle: saved.id } };
    }
    const resolved = await resolveBody(saved.vehicle, label);
    return { ...resolved, record: resolved.ref, params: { vehicle: saved.id } };
  }
  if (which === "combo") {
    const spec = combo.readSpec();
    const built = await combo.build(spec);
    const body = { combination_spec: spec };
    const label = spec.title || `Built combination: ${built.combination.units.map((u) => u.id).join(" + ")}`;
    return { ref: body, label, record: null, body, combination: built.combination, params: { combination_spec: JSON.stringify(spec) } };
  }
  if (which === "build") {
    const spec = specFromForm();
    const built = await build(spec);
    showBuilt(built);
    return { ref: built.vehicle, label: spec.title || `Built ${spec.unit_type}`, record: built.vehicle, built, params: { spec: JSON.stringify(spec) } };
  }
  const text = $("#record-json").value.trim();
  let body;
  try {
    body = JSON.parse(text);
  } catch (err) {
    const e = new Error(`not JSON: ${err.message}`);
    e.control = $("#record-json");
    throw e;
  }
  const resolved = await resolveBody(body, body.title || "Pasted record");
  const ref = resolved.ref && typeof resolved.ref === "object" ? presetRecord(resolved.ref) : resolved.ref;
  if (ref && typeof ref === "object" && ref.combination) {
    return { ...resolved, ref, record: null, body: ref, combination: ref.combination, params: { record: JSON.stringify(body) } };
  }
  return { ...resolved, ref, record: ref, params: { record: JSON.stringify(body) } };
}

/** Restore the vehicle from the URL parameters; returns whether there is one to compute. */
export function fromParams(params) {
  if (params.get("combination_spec")) {
    try {
      combo.setPending(JSON.parse(params.get("combination_spec")));
      showPanel("combo");
      return true;
    } catch {
      return false;
    }
  }
  if (params.get("spec")) {
    try {
      specToForm(JSON.parse(params.get("spec")));
      showPanel("build");
      return true;
    } catch {
      return false;
    }
  }
  if (params.get("record")) {
    $("#record-json").value = params.get("record");
    showPanel("record");
    return true;
  }
  const id = params.get("vehicle");
  if (!id) return false;
  if (id.startsWith("veh_")) {
    $("#saved-id").value = id;
    showPanel("saved");
    return Boolean($("#api-key").value.trim());
  }
  $("#preset").dataset.pending = id;
  showPanel("preset");
  return true;
}
