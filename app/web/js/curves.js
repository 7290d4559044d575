// The assessed curves on screen and on paper. The rows live in a worker (curves-worker.js), so a result of any size
// never blocks the page: the screen shows one page of rows at a time (flagged curves first, worst first; sortable by
// any column, filterable), and the printout asks the worker for the flagged curves worst first and, room left, the
// others -- saying how many more the CSV download holds.

import { ApiError } from "./api.js";
import { $, clear, el, fieldLabel, fmt, grouped, num, scroller, signed } from "./dom.js";

// ------------------------------------------------------------------------------------------ the worker

let worker = null;
let sequence = 0;
const waiting = new Map();

function startWorker() {
  const w = new Worker("/web/js/curves-worker.js", { type: "module" });
  w.onmessage = (event) => {
    const { id, error, ...answer } = event.data;
    const promise = waiting.get(id);
    waiting.delete(id);
    if (!promise) return;
    if (error) promise.reject(error.problem ? new ApiError(error.problem) : new Error(error.message));
    else promise.resolve(answer);
  };
  return w;
}

/** Start the worker (and the number formats) while the page is idle, so the first result does not pay for them. */
export function warm() {
  const start = () => {
    worker ??= startWorker();
    grouped(1234.5, 0);
    grouped(1234.5, 1);
  };
  if ("requestIdleCallback" in window) requestIdleCallback(start, { timeout: 5000 });
  else setTimeout(start, 1000);
}

/** One question to the worker: `load` {rows}, `fetch` {url, key} (a job's CSV result), `view`, `slice`, `print`. */
export function ask(op, message = {}) {
  worker ??= startWorker();
  sequence += 1;
  const id = sequence;
  return new Promise((resolve, reject) => {
    waiting.set(id, { resolve, reject });
    worker.postMessage({ id, op, ...message });
  });
}

// ------------------------------------------------------------------------------------------ columns

const blank = (v) => v === null || v === undefined || v === "";
const yesNo = (v) => (blank(v) ? "-" : v ? "yes" : "no");
const GOVERNED = { "side-friction": "side friction", rollover: "rollover" };

/**
 * The curves' columns: the curve (its name in road order, C1, C2, ...), what a reader acts on (flag, margin, safe and
 * posted speed, what governs), where it is (station, direction, the file's own id), then the inputs and the speeds
 * behind the verdict. A field the service adds later is shown after these, its label made from its name and unit.
 * `width` [ch]: the column's width on screen (a fixed layout: a page of rows is laid out without measuring every cell,
 * and the columns keep their widths from page to page).
 */
export const COLUMNS = [
  { key: "name", label: "Curve", text: true, width: 7 },
  { key: "flagged", label: "Flag", format: (v) => (v ? "\u26a0 flagged" : "ok"), nowrap: true, width: 10 },
  { key: "margin_kmh", label: "Margin [km/h]", format: (v) => signed(v, 1), width: 9 },
  { key: "safe_speed_kmh", label: "Safe speed [km/h]", format: (v) => fmt(v, 1), width: 9 },
  { key: "posted_speed_kmh", label: "Posted [km/h]", format: (v) => fmt(v, 0), width: 8 },
  { key: "governed_by", label: "Governed by", format: (v) => GOVERNED[v] || v, text: true, width: 10 },
  { key: "vehicle", label: "Vehicle", text: true, wrap: true, width: 14 },
  { key: "station_m", label: "Station [m]", format: (v) => grouped(v, 0), width: 10 },
  { key: "direction", label: "Turns", text: true, width: 7 },
  { key: "id", label: "Id in the file", text: true, wrap: true, width: 14 },
  { key: "radius_m", label: "Radius R [m]", format: (v) => grouped(v, 0), width: 9 },
  { key: "radius_std_m", label: "\u00b1 R [m] (1 s.e.)", format: (v) => fmt(v, 1), width: 9 },
  { key: "superelevation_percent", label: "Superelevation e [%]", format: (v) => fmt(v, 2), width: 14 },
  { key: "grade_percent", label: "Grade [%]", format: (v) => signed(v, 1), width: 7 }, // + uphill
  { key: "srt_g", label: "SRT [g]", format: (v) => fmt(v, 3), width: 7 },
  { key: "rollover_speed_kmh", label: "Rollover speed [km/h]", format: (v) => fmt(v, 1), width: 10 },
  { key: "side_friction_speed_kmh", label: "Side-friction speed [km/h]", format: (v) => fmt(v, 1), width: 10 },
  { key: "standard_min_radius_m", label: "Standard's Rmin [m]", format: (v) => grouped(v, 0), width: 10 },
  { key: "meets_standard_min_radius", label: "Meets Rmin", format: yesNo, text: true, width: 7 },
  // the sign and the truck's speed profile (docs/advisory.md): the worker flattens `treatment` and
  // `truck_rollover_warning` to the CSV's columns, so both answers sort and filter alike
  { key: "advisory_speed_kmh", label: "Advisory speed (plaque)", format: (v) => advisoryText(v), nowrap: true, width: 13, advisory: true },
  { key: "treatment_devices", label: "Treatment (signs)", format: (v, r) => treatmentText(v, r), text: true, wrap: true, width: 26, advisory: true },
  { key: "truck_rollover_warning", label: "W1-13 truck rollover warning", format: (v) => (blank(v) ? "-" : v ? "\u26a0 recommended" : "not recommended"), text: true, width: 12, advisory: true },
  { key: "approach_speed_kmh", label: "Approach speed [km/h]", format: (v) => fmt(v, 1), width: 9, advisory: true },
  { key: "required_deceleration_mps2", label: "Required deceleration [m/s\u00b2]", format: (v) => fmt(v, 2), width: 11, advisory: true },
  { key: "profile_reason", label: "Why no profile figure", text: true, wrap: true, width: 22, advisory: true },
  { key: "error", label: "Error", text: true, wrap: true, width: 24 },
];

/** The plaques' units and increment of the answer shown (its `advisory`; a job's from its result's head). */
export const advisory = { units: null, increment: null };

const MPH = 1.609344; // km per mile (exact)

/** The advisory speed as the plaque shows it: "55 mph (88.5 km/h)" with US plaques, "90 km/h" with metric ones. */
function advisoryText(v) {
  if (blank(v)) return "-";
  if (advisory.units === "us") return `${fmt(v / MPH, 0)} mph (${fmt(v, 1)} km/h)`;
  if (advisory.units === "metric") return `${fmt(v, 0)} km/h`;
  return `${fmt(v, 1)} km/h`;
}

/** The devices in words; none called for, or none without a posted speed (the difference needs one). */
function treatmentText(v, r) {
  if (!blank(v)) return v;
  if (blank(r?.advisory_speed_kmh)) return "-";
  return blank(r?.posted_speed_kmh) ? "none judged (no posted speed)" : "none called for";
}

/** Keys of the sign's and the profile's columns (printed in a table of their own: the curves' table fills A4). */
export const ADVISORY_KEYS = new Set(COLUMNS.filter((c) => c.advisory).map((c) => c.key));

/** Fields not shown as columns: the vehicle's place in a fleet's CSV, the targets (the SRT section has them), the
 * intermediate values of the verdict, the page's own order. */
const HIDDEN = new Set([
  "vehicle_index", "vehicle_preset", "vehicle_saved_id", "road_order", "targets", "level_road_srt",
  "tilt_table_angle_deg", "side_friction", "side_friction_clamped", "superelevation_source", "coordinates",
  "assessment", "vehicles", "governing_vehicle", "start_m", "end_m", "treatment", "advisory_speed_mph",
]); // prettier-ignore
const HIDDEN_PATTERN = /^(meets_.+|margin_.+_g)$/; // a CSV's target columns (meets_general, margin_general_g)

/** A label from a field's name: `deflection_deg` -> "Deflection [deg]", `bend_start_m` -> "Bend start [m]". */
export const labelOf = (key) => fieldLabel(key);

const generic = (v) => (typeof v === "boolean" ? yesNo(v) : typeof v === "number" ? num(v, 3) : blank(v) ? "-" : String(v));

/** The columns of rows whose fields are `keys`: the known ones that carry a value (the flag always), then the rest. */
export function columnsOf(keys) {
  const have = new Set(keys);
  // a row with an advisory speed has every sign and profile column, blank where the profile gives no figure (its
  // reason says why)
  const advised = have.has("advisory_speed_kmh");
  const known = COLUMNS.filter((c) => have.has(c.key) || c.key === "flagged" || c.key === "name" || (advised && c.advisory));
  const knownKeys = new Set(COLUMNS.map((c) => c.key));
  const extra = keys
    .filter((k) => !knownKeys.has(k) && !HIDDEN.has(k) && !HIDDEN_PATTERN.test(k))
    .map((k) => ({ key: k, label: labelOf(k), format: generic, text: false, width: 10 }));
  return [...known, ...extra];
}

const cellClass = (c) => (c.nowrap ? "nowrap" : [c.text ? "text" : null, c.wrap ? "wrap" : null].filter(Boolean).join(" ") || null);

function cells(columns, r) {
  return columns.map((c) => el("td", { class: cellClass(c) }, c.format ? c.format(r[c.key], r) : blank(r[c.key]) ? "-" : r[c.key]));
}

// ------------------------------------------------------------------------------------------ the summary line

/** "20,000 curves, 2,165 flagged, ..., smallest margin −66.4 km/h (C812, id K812)" from the worker's counts. */
export function summaryText(stats, { vehicleText, lengthM, governing } = {}) {
  const parts = [`${grouped(stats.curves, 0)} curves`, `${grouped(stats.flagged, 0)} flagged${governing ? " for their governing vehicle" : ""}`];
  if (vehicleText) parts.push(vehicleText);
  if (typeof lengthM === "number") parts.push(`route ${fmt(lengthM / 1000, 2)} km`);
  if (stats.below_standard_min_radius) parts.push(`${grouped(stats.below_standard_min_radius, 0)} below the standard's minimum radius`);
  if (stats.refused) parts.push(`${grouped(stats.refused, 0)} refused`);
  if (stats.min_margin_kmh !== null) parts.push(`smallest margin ${signed(stats.min_margin_kmh, 1)} km/h (${curveName(stats.worst)})`);
  if (stats.min_safe_speed_kmh !== null) parts.push(`lowest safe speed ${fmt(stats.min_safe_speed_kmh, 1)} km/h`);
  return `${parts.join(", ")}.`;
}

/** "C812 at 12,345 m, id K812": a curve by its name, station and the file's id. */
export function curveName(r) {
  if (!r) return "-";
  const at = typeof r.station_m === "number" ? ` at ${grouped(r.station_m, 0)} m` : "";
  return `${r.name}${at}, id ${r.id}`;
}

// ------------------------------------------------------------------------------------------ the table on screen

/** Rows a page of the table shows; a setting of the module (a test may change it). */
export const settings = { pageRows: 25, printRows: 500 };

const view = { token: 0, columns: [], sort: null, filter: { flagged: false, text: "" }, vehicle: null, first: 0, count: 0, box: null };

/** Show the rows the worker holds in `box`: controls (filter, find), the table, the pager. Resolves when drawn. */
export async function showTable(box, { keys, vehicle = null }) {
  Object.assign(view, { box, columns: columnsOf(keys), sort: null, filter: { flagged: false, signed: false, warning: false, text: "" }, vehicle, first: 0 });
  const filter = el(
    "select",
    { id: "curves-filter" },
    el("option", { value: "all" }, "all curves, flagged first"),
    el("option", { value: "flagged" }, "flagged curves only"),
    // the sign's filters where the rows carry advisory speeds
    keys.includes("advisory_speed_kmh") ? el("option", { value: "signed" }, "curves whose treatment calls for signs") : null,
    keys.includes("advisory_speed_kmh") ? el("option", { value: "warning" }, "curves with a W1-13 truck rollover warning") : null,
  );
  const find = el("input", { id: "curves-find", type: "search", spellcheck: "false", placeholder: "C12 or the file's id" });
  filter.addEventListener("change", () => refilter({ flagged: filter.value === "flagged", signed: filter.value === "signed", warning: filter.value === "warning" }));
  let timer = null;
  find.addEventListener("input", () => {
    clearTimeout(timer);
    timer = setTimeout(() => refilter({ text: find.value.trim() }), 250);
  });
  clear(box).append(
    el(
      "div",
      { class: "grid table-controls" },
      el("div", { class: "field" }, el("label", { for: "curves-filter" }, "Show"), filter),
      el("div", { class: "field" }, el("label", { for: "curves-find" }, "Find a curve"), find),
    ),
    el("div", { id: "curves-table-box" }),
    el("nav", { class: "pager", "aria-label": "Pages of the curves table" }),
  );
  await refresh();
}

async function refilter(change) {
  Object.assign(view.filter, change);
  view.first = 0;
  await refresh();
}

/** Ask the worker for the view (order and filter) and draw its current page. */
async function refresh() {
  view.token += 1;
  const token = view.token;
  const { count } = await ask("view", { sort: view.sort, filter: view.filter, vehicle: view.vehicle });
  if (token !== view.token) return;
  view.count = count;
  await drawPage(token);
}

async function drawPage(token = view.token) {
  const { rows } = await ask("slice", { start: view.first, end: view.first + settings.pageRows });
  if (token !== view.token) return;
  const head = el(
    "tr",
    {},
    view.columns.map((c) =>
      el(
        "th",
        { scope: "col", class: cellClass(c), "aria-sort": view.sort?.key === c.key ? view.sort.direction : "none" },
        el("button", { type: "button", class: "sort", "data-key": c.key, title: `Sort by ${c.label}` }, c.label),
      ),
    ),
  );
  const body = rows.map((r) => el("tr", { class: r.flagged ? "flagged" : null, "data-id": r.id }, cells(view.columns, r)));
  const caption = view.sort ? "Sorted by the column marked; select a heading to sort." : "Flagged curves first, worst margin first, then the others in road order; select a heading to sort.";
  // widths through the CSSOM (the page's Content-Security-Policy refuses style attributes)
  const cols = view.columns.map((c) => {
    const col = el("col");
    col.style.width = `${c.width + 2}ch`;
    return col;
  });
  const t = el("table", { id: "curves-table", class: "fixed" }, el("caption", { class: "hint" }, caption), el("colgroup", {}, cols), el("thead", {}, head), el("tbody", {}, body));
  const tableBox = clear($("#curves-table-box", view.box));
  tableBox.append(scroller("Assessed curves (scrolls sideways)", t, true));
  // a full page (more rows than the box shows) gets a box of a fixed height, laid out apart from the page
  tableBox.querySelector(".table-wrap").classList.toggle("full", rows.length > 12);
  head.addEventListener("click", (ev) => {
    const button = ev.target.closest("button.sort");
    if (!button) return;
    const key = button.dataset.key;
    view.sort = { key, direction: view.sort?.key === key && view.sort.direction === "ascending" ? "descending" : "ascending" };
    view.first = 0;
    refresh().then(() => view.box.querySelector(`button.sort[data-key="${key}"]`)?.focus());
  });
  drawPager();
}

function drawPager() {
  const nav = clear($("nav.pager", view.box));
  const size = settings.pageRows;
  const last = Math.max(0, Math.floor((view.count - 1) / size) * size);
  const go = (first) => () => {
    view.first = first;
    drawPage();
  };
  const button = (id, text, first, enabled) => el("button", { type: "button", id, disabled: !enabled, onclick: go(first) }, text);
  const shown = view.count ? `Rows ${grouped(view.first + 1, 0)}\u2013${grouped(Math.min(view.first + size, view.count), 0)} of ${grouped(view.count, 0)}` : "No curve matches";
  nav.append(
    button("curves-first", "First", 0, view.first > 0),
    button("curves-prev", "Previous", Math.max(0, view.first - size), view.first > 0),
    el("span", { id: "curves-shown", role: "status" }, shown),
    button("curves-next", "Next", view.first + size, view.first + size < view.count),
    button("curves-last", "Last", last, view.first < last),
  );
}

// ------------------------------------------------------------------------------------------ the printout

/** Let the page answer between two pieces of work (so that building the printout never blocks it). */
const pause = () => new Promise((resolve) => setTimeout(resolve, 0));

/**
 * The road's part of the printout: its summary (the file, the vehicle, the counts, the worst curve), the outline, and
 * the curves -- every flagged one worst first, then the others in road order, at most `settings.printRows`; a line
 * says how many more the CSV download holds.
 */
export async function printout({ stats, fileName, vehicleText, lengthM, governing, outline, downloadName }) {
  const { rows, flagged, others, printedFlagged, printedOthers } = await ask("print", { max: settings.printRows, vehicle: view.vehicle });
  const facts = [
    ["File assessed", fileName],
    ["Vehicle", vehicleText],
    ["Curves", grouped(stats.curves, 0)],
    ["Flagged", grouped(stats.flagged, 0)],
    ["Worst margin", stats.min_margin_kmh === null ? "-" : `${signed(stats.min_margin_kmh, 1)} km/h, ${curveName(stats.worst)}`],
  ];
  if (typeof lengthM === "number") facts.push(["Route length", `${fmt(lengthM / 1000, 2)} km`]);
  if (stats.below_standard_min_radius) facts.push(["Below the standard's minimum radius", grouped(stats.below_standard_min_radius, 0)]);
  if (stats.refused) facts.push(["Refused", grouped(stats.refused, 0)]);
  const summary = el(
    "div",
    { class: "road-summary keep" },
    el("p", { class: "verdict-line" }, summaryText(stats, { lengthM, governing })),
    el("dl", { class: "facts" }, facts.flatMap(([k, v]) => [el("dt", {}, k), el("dd", {}, v)])),
  );
  const left = flagged - printedFlagged + others - printedOthers;
  const what = printedFlagged < flagged
    ? `The ${grouped(printedFlagged, 0)} worst of the ${grouped(flagged, 0)} flagged curves are printed, worst first.`
    : printedOthers < others
      ? `All ${grouped(flagged, 0)} flagged curves are printed, worst first, then ${grouped(printedOthers, 0)} of the ${grouped(others, 0)} others in road order.`
      : `All ${grouped(flagged + others, 0)} curves are printed: the ${grouped(flagged, 0)} flagged ones first, worst first, then the others in road order.`;
  const note = el("p", { class: "print-note" }, what, left ? ` The other ${grouped(left, 0)} curves are in the CSV download (${downloadName}).` : "");
  const all = columnsOf(stats.keys);
  // the curves' table fills A4 landscape: the sign's and the profile's columns are a second table of the same rows,
  // each curve named again by its name, id, station and speeds
  const columns = all.filter((c) => !ADVISORY_KEYS.has(c.key));
  const signColumns = all.filter((c) => ["name", "id", "station_m", "posted_speed_kmh", "safe_speed_kmh"].includes(c.key) || ADVISORY_KEYS.has(c.key));
  const t = await printTable(columns, rows, "curves-print");
  const parts = [summary, figure(outline), el("h4", { class: "with-next" }, "Curves"), note, t];
  if (stats.keys.includes("advisory_speed_kmh")) {
    parts.push(
      el("h4", { class: "with-next signs-title" }, "Signs and the truck's speed profile"),
      el("p", { class: "print-note" }, "The same curves in the same order: the advisory speed on the plaque, the treatment, the W1-13 warning and the profile's figures."),
      signsNotes(stats, advisory, { print: true }),
      await printTable(signColumns, rows, "curves-print signs-print"),
    );
  }
  return parts;
}

function figure(outline) {
  return outline ? el("figure", { class: "outline keep" }, outline.cloneNode(true), el("figcaption", { class: "hint" }, "Route outline (north up); flagged curves in red.")) : null;
}

/** A printed table of `rows`, built 25 rows at a time (the page answers in between). */
async function printTable(columns, rows, cls) {
  const head = el("thead", {}, el("tr", {}, columns.map((c) => el("th", { scope: "col", class: cellClass(c) }, c.label))));
  const body = el("tbody");
  for (let i = 0; i < rows.length; i += 25) {
    body.append(...rows.slice(i, i + 25).map((r) => el("tr", { class: r.flagged ? "flagged" : null }, cells(columns, r))));
    await pause();
  }
  return el("table", { class: cls }, head, body);
}

// ------------------------------------------------------------------------------------------ signs and methods

const plural = (n, word) => `${grouped(n, 0)} ${word}${n === 1 ? "" : "s"}`;

/** "Signs to post: advisory speed plaque (W13-1) at 3 curves; ...": the devices over the curves shown. */
export function signsText(stats) {
  if (!stats.advised) return "";
  const devices = Object.entries(stats.devices || {}).map(([d, n]) => `${d} at ${plural(n, "curve")}`);
  const warn = stats.warnings ? `a W1-13 truck rollover warning at ${plural(stats.warnings, "curve")} (this service's rule)` : "no W1-13 truck rollover warning";
  if (!devices.length) return `Signs to post: none called for by the posted-advisory difference; ${warn}.`;
  return `Signs to post: ${devices.join("; ")}; ${warn}.`;
}

/** The plaque's rounding in words, by the answer's units and increment (docs/advisory.md, "The plaque"). */
function plaqueWords(adv) {
  if (adv?.units === "us") return `US plaques in multiples of ${num(adv.increment ?? 5, 0)} mph (TxDOT Direct Method, Step 2: +1 mph, then down to a multiple of 5 mph), shown with the speed in km/h`;
  if (adv?.units === "metric") return `metric plaques in multiples of ${num(adv.increment ?? 10, 0)} km/h (rounded down: assumed, no metric rule was read)`;
  return "the plaque's increment is not in this result";
}

/**
 * How the advisory speeds were found, in words: the primary method is unverified (no number from it), which method
 * sets them, the plaque's rounding, and the long sources the answer states once (`advisory`). `adv` may be null.
 */
export function signsNotes(stats, adv, { print = false } = {}) {
  // the service's own words where the answer states them (advisory.primary_method, method_source), else the same
  // facts as docs/advisory.md gives them
  const method = adv?.primary_method && adv?.method_source
    ? [
        `Primary method ${adv.primary_method.includes("unverified") ? "unverified" : "used"}: ${adv.primary_method}. `,
        `Each advisory speed here: ${adv.method_source}.`,
      ]
    : [
        "Primary method unverified: the Design Method that FHWA-SA-11-22 (2011) and TxDOT name (Bonneson, Pratt, Miles and Carlson's curve speed model) could not be read in its primary text, so the service computes no speed from it and none is shown. ",
        "Without a measured car speed (TxDOT's Direct Method), each advisory speed is the newest legacy ball-bank criterion's (MUTCD 2009, 16/14/12 degrees by speed; unverified).",
      ];
  const items = [
    el("li", { class: "unverified-method" }, ...method),
    el("li", {}, `Plaques: ${plaqueWords(adv)}. Curves within 600 ft (183 m) of each other share one sign, its lowest speed (TxDOT).`),
  ];
  if (adv?.treatment_source) items.push(el("li", {}, `Treatment: ${adv.treatment_source}.`));
  if (adv?.truck_rollover_warning_rule) items.push(el("li", {}, `W1-13: ${adv.truck_rollover_warning_rule}.`));
  return el(
    "div",
    { class: `signs-notes${print ? " keep" : ""}` },
    el("p", { class: "signs-line" }, signsText(stats)),
    el("ul", { class: "method-notes" }, items),
  );
}
