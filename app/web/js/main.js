// The calculator page: wiring. Loads what the deployment offers (its OpenAPI document, the models, presets,
// design standards, components), restores the state from the URL and computes when the link names a vehicle.

import * as alignment from "./alignment.js";
import * as api from "./api.js";
import * as combination from "./combination.js";
import * as combo from "./combobuilder.js";
import * as curves from "./curves.js";
import * as dynamics from "./dynamics.js";
import * as filecheck from "./filecheck.js";
import { $, $$, clear, cueStaticTables, el, num } from "./dom.js";
import { clearErrors, localError, showError } from "./errors.js";
import { applyParams, caseFields, rememberDefaults, stateParams, writeUrl } from "./form.js";
import * as results from "./results.js";
import * as road from "./road.js";
import * as stale from "./stale.js";
import * as summary from "./summary.js";
import * as vehicle from "./vehicle.js";

const page = { models: [], last: null, modelChosen: false };

const status = (text) => {
  $("#page-status").textContent = text;
};

/** Run `task` with `button` disabled; errors go to the fields of `scope` or its form-level box. */
async function guarded(button, scope, box, task) {
  clearErrors(scope);
  if (button) button.disabled = true;
  try {
    return await task();
  } catch (err) {
    if (err.control) localError(err.control, err.message);
    else showError(err, scope, box);
    return undefined;
  } finally {
    if (button) button.disabled = false;
  }
}

// ------------------------------------------------------------------------------------------ models

function fillModels(models) {
  page.models = models;
  const select = $("#model");
  for (const m of models) select.append(el("option", { value: m.id }, m.name)); // the name on screen, the id in links
  const initial = models.find((m) => m.default)?.id || models[0]?.id;
  select.value = select.dataset.pending && models.some((m) => m.id === select.dataset.pending) ? select.dataset.pending : initial;
  select.dataset.initial = initial;
}

/** What the whole-combination model accounts for (engine/models/registry.py, `combination_takes`), for a service
 * whose GET /v1/models does not say it yet. */
const WHOLE_COMBINATION_TAKES = ["bank", "slope", "d1", "d2", "d3", "overweight", "rear_llt_limit"];

const modelInfo = () => page.models.find((m) => m.id === $("#model").value);

/** Enable the inputs the model takes, and only the models the vehicle supports. */
function syncModel() {
  const supported = vehicle.supportedModels();
  const select = $("#model");
  for (const option of select.options) option.disabled = Boolean(supported) && !supported.includes(option.value);
  // a model the page chose for the last vehicle goes back to the vehicle's default when the vehicle supports it
  // (a combination: the whole-combination model; else the service's default)
  const wanted = vehicle.defaultModel() || select.dataset.initial;
  if (!page.modelChosen && select.querySelector(`option[value="${wanted}"]`) && !select.querySelector(`option[value="${wanted}"]`).disabled) {
    select.value = wanted;
  }
  if (select.selectedOptions[0]?.disabled) select.value = supported[0];
  const m = modelInfo();
  if (!m) return;
  // a combination solved as a whole takes the road and load inputs its model lists for combinations
  // (`combination_takes`); a service that does not list them gets the whole-combination model's own list
  let takesList = m.takes;
  if (vehicle.choosesCombination()) takesList = m.combination_takes || (m.id === "combination" ? WHOLE_COMBINATION_TAKES : m.takes);
  for (const box of $$("[data-takes]")) {
    const takes = takesList.includes(box.dataset.takes);
    box.classList.toggle("disabled", !takes);
    for (const c of $$("input, select", box)) c.disabled = !takes;
  }
  $("#model-info").textContent = `${m.name}: ${m.summary} ${m.equation}; ${m.reference}.`;
}

// ------------------------------------------------------------------------------------------ computing

async function compute() {
  const section = $("#vehicle-section").parentElement;
  const done = await guarded($("#compute"), section, $("#case-error"), async () => {
    $("#results").setAttribute("aria-busy", "true");
    const v = await vehicle.current();
    syncModel(); // a saved vehicle read just now: its kind's model (a combination's) before the case is read
    const request = caseFields();
    const result = await api.post("/v1/srt", { vehicle: v.ref, ...request });
    results.showResult(result, modelInfo());
    combination.show(v.combination || null, result);
    offerPayload(result, v);
    stale.fresh(["srt", "builder", "combo", "summary"]);
    const link = writeUrl(stateParams(v.params));
    page.last = { vehicle: v, request, result, figures: [], link, design: null, speed: null };
    return page.last;
  });
  $("#results").setAttribute("aria-busy", "false");
  if (!done) stale.mark(["srt", "design", "speed", "limits", "builder", "combo", "summary"], stale.FAILED);
  if (done) {
    status("");
    // the figures, the road design and the curve speed of the same case, side by side
    const { targets: _t, ...plotRequest } = done.request;
    const figures = results.showPlots({ vehicle: done.vehicle.ref, ...plotRequest }, Boolean(modelInfo()?.curves));
    await Promise.all([figures.then((f) => (done.figures = f)), roadDesign(), curveSpeed()]);
    summary.update(done);
  }
  counted("computations");
}

/**
 * A vehicle below a target is offered what load would meet it: the payload table of a built vehicle (the
 * TERNZ-style table: largest payload by load height), else the largest CG height (or load offset) by overweight.
 */
function offerPayload(result, v) {
  const missed = result.targets.filter((t) => !t.meets).sort((a, b) => a.target_g - b.target_g);
  const box = $("#payload-offer");
  box.hidden = !missed.length || !$("#limits-form").closest("[data-needs]") || $("#limits-form").closest("[data-needs]").hidden;
  if (box.hidden) return;
  const target = missed[0].target_g;
  const what = v.built ? "Acceptable payload table" : v.combination ? "Acceptable load height by overweight" : "Acceptable CG height by overweight";
  $("#payload-offer-text").textContent = `Below the ${num(target, 3, 2)} g ${results.targetName(missed[0].name)} target: what load would meet it?`;
  const button = $("#payload-offer-button");
  button.textContent = `${what} for ${num(target, 3, 2)} g`;
  button.dataset.target = String(target);
}

/** Count finished runs on <body data-*> (how scripts and tests know that the page has answered). */
function counted(name) {
  document.body.dataset[name] = String(Number(document.body.dataset[name] || 0) + 1);
}

/** The road-design part of a computation (the minimum radius plot and table for the same vehicle and case). */
async function roadDesign() {
  const { vehicle: v, request } = page.last;
  const design = await guarded($("#road-compute"), $("#road-section"), $("#road-error"), () => road.minRadius(v.ref, request));
  if (!design) stale.mark(["design"], stale.FAILED);
  if (design) {
    stale.fresh(["design"]);
    page.last.design = design;
    page.last.link = writeUrl(stateParams(v.params));
  }
}

async function curveSpeed() {
  const { vehicle: v, request } = page.last;
  const speed = await guarded($("#speed-compute"), $("#speed-form"), $("#speed-error"), () => road.curveSpeed(v.ref, request));
  if (speed === undefined) stale.mark(["speed", "advisory"], stale.FAILED);
  if (speed !== undefined) {
    stale.fresh(["speed", "advisory"]);
    page.last.speed = speed;
    page.last.link = writeUrl(stateParams(v.params));
  }
}

/** The progress bar of an alignment job: its value, and done/total in words. */
function showJob(job) {
  const bar = $("#alignment-progress");
  bar.value = job.progress;
  const unit = job.unit || "rows";
  $("#alignment-progress-text").textContent = `${Math.round(100 * job.progress)} % (${job.done} of ${job.total} ${unit}; job ${job.status})`;
}

/** The bearer key when one is typed (a job is the key's own), else none: the service says if it needs one. */
const typedKey = () => $("#api-key").value.trim() || undefined;

/**
 * A job: {job: {url, key}} for an alignment (its result is read by the curves' worker), {result} for a route; when
 * the service wants a bearer key for jobs and none is typed, the same request synchronously: {result}.
 */
async function jobOrRequest(path, request, key, signal, operation) {
  try {
    const url = await alignment.runJob(request, { operation, key, onStatus: showJob, signal, read: false });
    return operation === "alignments.assess" ? { job: { url, key } } : { result: await api.get(url, { key }), stored: { url, key } };
  } catch (err) {
    if (!(err instanceof api.ApiError) || err.problem.status !== 401 || key) throw err;
    $("#alignment-progress-text").textContent = "one request (a job needs the bearer key under \u201cSaved vehicles\u201d)";
    $("#alignment-cancel").hidden = true;
    return { result: await api.post(path, request) };
  }
}

/**
 * What the chosen file carries and still needs, shown beside the boxes before any request; returns the note that
 * blocks the request (a file that is not text, a superelevation nobody gave), or null.
 */
const lastCheck = { file: null, inputs: "", blocker: null };

async function checkFile() {
  const file = $("#alignment-file").files[0];
  const info = $("#alignment-file-info");
  if (!file) {
    filecheck.showNotes([]);
    info.textContent = "";
    return null;
  }
  // the same file with the same boxes was read when it was chosen: not again at Assess (a file can be large)
  const inputs = ["#al-e", "#al-emax", "#al-posted", "#al-grade"].map((id) => $(id).value).join("|");
  if (lastCheck.file === file && lastCheck.inputs === inputs) return lastCheck.blocker;
  const blocker = await readFile(file, info);
  Object.assign(lastCheck, { file, inputs, blocker });
  return blocker;
}

/** Read the file's head: whether it is text, what it carries, what it needs (shown beside the boxes). */
async function readFile(file, info) {
  const bytes = new Uint8Array(await file.slice(0, 65536).arrayBuffer());
  if (!filecheck.isText(bytes)) {
    const note = { box: "#alignment-file", blocks: true, text: `${file.name} is not a text file (it holds binary data: an image, a spreadsheet's workbook, ...): choose a CSV table, or a LandXML, GPX or GeoJSON file.` };
    info.textContent = "";
    filecheck.showNotes([note]);
    return note;
  }
  const text = await file.slice(0, 4_000_000).text();
  const kind = alignment.formatOf(file.name, text);
  const has = filecheck.carries(kind, text);
  const whole = file.size <= 4_000_000;
  info.textContent = filecheck.describe(kind, file.name, text, has, whole ? alignment.rowCount(kind, text) : null);
  const notes = filecheck.needs(kind, file.name, has);
  filecheck.showNotes(notes);
  return notes.find((n) => n.blocks) || null;
}

async function assessFile() {
  const section = $("#alignment-section");
  const box = $("#alignment-progress-box");
  const bar = $("#alignment-progress");
  const cancel = $("#alignment-cancel");
  const aborter = new AbortController();
  const onCancel = async () => {
    aborter.abort();
    await alignment.cancelJob().catch(() => undefined);
  };
  const assessed = await guarded($("#alignment-assess"), section, $("#alignment-error"), async () => {
    const file = $("#alignment-file").files[0];
    if (!file) throw Object.assign(new Error("choose a file"), { control: $("#alignment-file") });
    // what the file still needs is said beside its box before any request: nothing is sent without it
    const blocker = await checkFile();
    if (blocker) {
      $(blocker.box).focus();
      return false;
    }
    const text = await file.text();
    const kind = alignment.formatOf(file.name, text);
    // a saved fleet is its key's own: the key goes with every request (else the key typed, if any, for a job)
    const fleet = alignment.fleetId();
    const key = fleet ? vehicle.apiKey() : typedKey();
    const v = fleet ? null : await vehicle.current();
    syncModel();
    const [path, request] = await alignment.buildRequest(kind, text, v?.ref, caseFields());
    const job = await alignment.wantsJob(path, alignment.rowCount(kind, text));
    box.hidden = false;
    bar.removeAttribute("value"); // indeterminate until the job reports progress (or the one request answers)
    $("#alignment-progress-text").textContent = job ? "submitting the job" : "one request";
    cancel.hidden = !job;
    cancel.addEventListener("click", onCancel, { once: true });
    let answer;
    try {
      answer = job ? await jobOrRequest(path, request, key, aborter.signal, job) : { result: await api.post(path, request, { key }) };
    } finally {
      cancel.hidden = true;
      cancel.removeEventListener("click", onCancel);
      box.hidden = !job; // a job's bar stays, at 100 % or where it stopped
    }
    Object.assign(alignment.state, { path, request, key });
    const lines = kind === "geojson" || kind === "gpx" ? alignment.routeLines(kind, text) : null;
    const vehicleText = fleet ? `saved fleet ${fleet}` : v.label;
    await alignment.render({ ...answer, kind, lines, fileName: file.name, vehicleText });
    return true;
  });
  if (assessed) stale.fresh(["alignment"]);
  else stale.mark(["alignment"], stale.FAILED);
  counted("assessments");
}

// ------------------------------------------------------------------------------------------ wiring

function watchInputs() {
  stale.watch($("#vehicle-section"), "vehicle");
  stale.watch($("#case-form"), "case");
  stale.watch($("#road-form"), "road");
  $("#standard").addEventListener("change", () => stale.mark(stale.DEPENDS.standard));
  stale.watch($("#speed-form"), "speed");
  stale.watch($("#super-form"), "superelevation");
  stale.watch($("#limits-form"), "limits");
  stale.watch($("#alignment-form"), "alignment");
  stale.watch($("#dynamics-form"), "dynamics");
}

function wire() {
  cueStaticTables();
  watchInputs();
  $("#case-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    compute();
  });
  // the road forms recompute everything, so the figures, the tables and the summary describe one case
  for (const id of ["#road-form", "#speed-form"]) {
    $(id).addEventListener("submit", (ev) => {
      ev.preventDefault();
      compute();
    });
  }
  $("#super-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    guarded($("#super-compute"), $("#super-form"), $("#super-error"), road.superelevation).then((out) => {
      if (out) summary.extra("superelevation", "Design superelevation of a curve", [$("#super-result"), $("#super-table")]);
      if (out) stale.fresh(["superelevation"]);
      else stale.mark(["superelevation"], stale.FAILED);
      counted("superelevations");
    });
  });
  $("#limits-form").addEventListener("submit", async (ev) => {
    ev.preventDefault();
    const out = await guarded($("#limits-compute"), $("#limits-form").parentElement, $("#limits-error"), async () => {
      const v = await vehicle.current();
      syncModel();
      const out = await road.limits(v.ref, caseFields(), { combination: Boolean(v.combination) });
      if (v.built && (await api.has("post", "/v1/vehicles/payload-table"))) await road.payloadTable(v.built.spec);
      summary.extra("limits", `Acceptable load for SRT ${$("#limit-target").value.trim()} g`, [$("#limits-result")]);
      return out;
    });
    if (out) stale.fresh(["limits"]);
    else stale.mark(["limits"], stale.FAILED);
    counted("limits");
  });
  // the fleet picker: the key's saved fleets (GET /v1/fleets); choosing one fills the fleet box
  $("#fleet-list").addEventListener("click", async () => {
    await guarded($("#fleet-list"), $("#alignment-section"), $("#alignment-error"), async () => {
      const fleets = await api.get("/v1/fleets?limit=100", { key: vehicle.apiKey() });
      const select = clear($("#fleet-choice"));
      select.append(el("option", { value: "" }, fleets.items.length ? "(this page's vehicle)" : "(no fleet saved under this key)"));
      for (const f of fleets.items) select.append(el("option", { value: f.id }, `${f.title} (${f.vehicles.length} vehicles: ${f.vehicles.join(", ")})`));
      select.value = $("#al-fleet").value.trim();
      select.hidden = false;
      $("#fleet-choice-label").hidden = false;
    });
    counted("fleets");
  });
  $("#fleet-choice").addEventListener("change", () => {
    $("#al-fleet").value = $("#fleet-choice").value;
  });
  $("#payload-offer-button").addEventListener("click", () => {
    $("#limit-target").value = $("#payload-offer-button").dataset.target;
    $("#limits-form").requestSubmit();
    $("#limits-result").scrollIntoView({ block: "start" });
  });
  // the road's part of the printout, built by alignment.js each time the curves shown change (a fleet's vehicle)
  document.addEventListener("curves-printout", (ev) => summary.extra("alignment", ev.detail.title, ev.detail.nodes, { lead: ev.detail.nodes[0], owned: true }));
  for (const id of ["#alignment-file", "#al-e", "#al-emax", "#al-posted", "#al-grade"]) {
    $(id).addEventListener("change", () => checkFile().catch(() => undefined));
  }
  $("#dynamics-form").addEventListener("submit", async (ev) => {
    ev.preventDefault();
    const out = await guarded($("#dynamics-compute"), $("#dynamics-section"), $("#dynamics-error"), () =>
      dynamics.screen(async () => {
        const v = await vehicle.current();
        syncModel();
        return v;
      }),
    );
    // printed after the summary, on A4 pages of its own
    if (out) summary.extra("dynamics", "Dynamics: PBS screening", out.nodes, { owned: true });
    if (out) stale.fresh(["dynamics"]);
    else stale.mark(["dynamics"], stale.FAILED);
    counted("screenings");
  });
  $("#alignment-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    assessFile();
  });
  $("#builder").addEventListener("submit", (ev) => {
    ev.preventDefault();
    compute();
  });
  for (const radio of $$('input[name="source"]')) {
    radio.addEventListener("change", () => {
      vehicle.showPanel(radio.value);
      syncModel();
    });
  }
  $("#preset").addEventListener("change", () => {
    vehicle.describePreset();
    syncModel();
  });
  $("#record-json").addEventListener("change", syncModel); // a pasted combination takes the combination's inputs
  $("#model").addEventListener("change", () => {
    page.modelChosen = true;
    syncModel();
  });
  $("#standard").addEventListener("change", road.describeStandard);
  $("#record-from-preset").addEventListener("click", () => {
    const p = vehicle.preset();
    if (!p) return;
    vehicle.presetBody(p).then((body) => {
      $("#record-json").value = JSON.stringify(body, null, 2);
      syncModel();
    });
  });
  const savedBox = $('[data-panel="saved"]');
  $("#saved-list").addEventListener("click", () => guarded($("#saved-list"), savedBox, $("#saved-error"), vehicle.listSaved));
  $("#saved-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    guarded($("#saved-load"), savedBox, $("#saved-error"), vehicle.loadSaved).then(syncModel);
  });
  $("#saved-choice").addEventListener("change", () => {
    if ($("#saved-choice").value) $("#saved-id").value = $("#saved-choice").value;
    syncModel();
  });
  $("#saved-id").addEventListener("change", syncModel);
  $("#key-form").addEventListener("submit", (ev) => {
    ev.preventDefault();
    guarded($("#save-vehicle"), $("#catalog-box"), $("#save-error"), async () => {
      if (vehicle.source() === "saved") {
        throw Object.assign(new Error("this vehicle is saved already: choose a preset, a built vehicle or a record"), {
          control: $("#save-title"),
        });
      }
      const v = await vehicle.current();
      const body = { title: $("#save-title").value.trim(), vehicle: v.built ? { spec: v.built.spec } : v.body || v.record };
      const saved = await api.post("/v1/vehicles", body, { key: vehicle.apiKey() });
      $("#save-info").textContent = `Saved as ${saved.id} (version ${saved.version}).`;
    });
  });
  $("#copy-link").addEventListener("click", async () => {
    const v = await vehicle.current().catch(() => null);
    const link = writeUrl(stateParams(v ? v.params : {}));
    try {
      await navigator.clipboard.writeText(link);
      status("The link is copied to the clipboard.");
    } catch {
      status(`Link: ${link}`);
    }
  });
  $("#print").addEventListener("click", () => window.print());
}

async function showOptionalParts() {
  for (const node of $$("[data-needs]")) {
    const [method, path] = node.dataset.needs.split(" ");
    node.hidden = !(await api.has(method, path));
  }
  if (await api.has("post", "/v1/routes/assess")) {
    $("#alignment-file").accept += ",.geojson,.json,.gpx,application/geo+json,application/gpx+xml";
    $("#alignment-formats").append(" Routes: GeoJSON (LineString) or GPX (track or route); above 20,000 points a route runs as a job too.");
  }
}

async function init() {
  wire();
  rememberDefaults();
  const params = applyParams();
  const wanted = vehicle.fromParams(params);
  // what this deployment has (its OpenAPI document) decides which optional lists are read
  const optional = (path) => api.has("get", path).then((yes) => (yes ? api.get(path) : null));
  const [models, presets, standards, components, combinations] = await Promise.all([
    api.get("/v1/models"),
    api.get("/v1/vehicles"),
    optional("/v1/design-standards"),
    optional("/v1/components"),
    optional("/v1/combinations"),
  ]);
  fillModels(models);
  page.modelChosen = Boolean(params.get("model"));
  vehicle.initBuilder();
  vehicle.fillPresets(presets, combinations || []);
  if (standards) road.fillStandards(standards);
  if (components) vehicle.fillComponents(components);
  await showOptionalParts();
  if (await api.has("post", "/v1/combinations/build")) await combo.init(combinations || []);
  if (await api.has("post", "/v1/pbs")) dynamics.fillChoices(combinations || []);
  syncModel();
  document.body.dataset.ready = "true";
  if (wanted) await compute();
  else if (params.get("vehicle")?.startsWith("veh_")) status("Enter the bearer key of the saved vehicle, then compute.");
  document.body.dataset.computed = "true";
  curves.warm();
}

init().catch((err) => status(`The page could not start: ${err.message}`));
