// Section 5: an alignment (CSV or LandXML: POST /v1/alignments/assess with the file's text, so any vehicle --
// preset, saved, built or pasted -- can be assessed) or a route (GeoJSON or GPX: POST /v1/routes/assess, when
// the deployment has it). A sortable table of the curves with their flags, the route's outline as an SVG with
// the flagged curves marked (no map tiles: the page works offline), a progress bar (POST /v1/jobs when the
// deployment has it, otherwise an indeterminate bar while the request runs) and downloads.

import * as api from "./api.js";
import { $, clear, download, el, fmt, scroller, signed, svgEl } from "./dom.js";
import { value } from "./form.js";
import { designFields, srtOptions } from "./road.js";

export const state = { result: null, request: null, path: null, key: undefined, kind: null, rows: [], outline: null, job: null };

const drop = (obj) => Object.fromEntries(Object.entries(obj).filter(([, v]) => v !== undefined));

/** csv | landxml | geojson | gpx, from the file's name and, failing that, its first characters. */
export function formatOf(name, text) {
  const ext = (name.split(".").pop() || "").toLowerCase();
  if (ext === "csv") return "csv";
  if (ext === "gpx") return "gpx";
  if (ext === "geojson" || ext === "json") return "geojson";
  if (ext === "xml" || ext === "landxml") return /<gpx[\s>]/.test(text.slice(0, 2000)) ? "gpx" : "landxml";
  const head = text.trimStart();
  if (head.startsWith("{")) return "geojson";
  if (head.startsWith("<")) return /<gpx[\s>]/.test(head.slice(0, 2000)) ? "gpx" : "landxml";
  return "csv";
}

/** The saved fleet typed in section 5 (`flt_...`): its vehicles are assessed instead of the page's vehicle. */
export const fleetId = () => value($("#al-fleet")) || undefined;

/** The request for the file: [path, body]. */
export async function buildRequest(kind, text, vehicleRef, caseRequest) {
  const fleet = fleetId();
  const common = drop({
    vehicle: fleet ? undefined : vehicleRef,
    fleet,
    ...srtOptions(caseRequest),
    targets: caseRequest.targets,
    ...designFields(),
    max_superelevation_percent: value($("#al-emax")),
  });
  if (kind === "csv") return ["/v1/alignments/assess", { ...common, csv: text }];
  if (kind === "landxml") {
    const landxml = drop({
      document: text,
      superelevation_percent: value($("#al-e")),
      grade_percent: value($("#al-grade")),
      posted_speed_kmh: value($("#al-posted")),
    });
    return ["/v1/alignments/assess", { ...common, landxml }];
  }
  if (!(await api.has("post", "/v1/routes/assess"))) {
    throw Object.assign(new Error("this deployment cannot assess routes (GeoJSON, GPX): upload CSV or LandXML"), {
      control: $("#alignment-file"),
    });
  }
  // the route's document: as text if the spec says the field is a string, else (GeoJSON) as the parsed object
  const schema = await api.requestSchema("post", "/v1/routes/assess");
  const asText = schema?.properties?.[kind]?.type === "string";
  const document = kind === "geojson" && !asText ? JSON.parse(text) : text;
  const route = drop({
    ...common,
    [kind]: document,
    superelevation_percent: value($("#al-e")),
    posted_speed_kmh: value($("#al-posted")),
  });
  return ["/v1/routes/assess", route];
}

/**
 * When a file goes through a job (POST /v1/jobs) with a progress bar and a Cancel button instead of one request:
 * an alignment above `jobRows` curves (`alignments.assess`), a route above `jobVertices` vertices (`routes.assess`,
 * when the deployment has that operation). Smaller files are one request. A setting of the module, so a test (or an
 * embedding page) can lower it.
 */
export const settings = { jobRows: 5000, jobVertices: 20000 };

/** The curves of an alignment file (CSV data rows, LandXML <Curve> elements); a route's vertices (GPX points,
 * GeoJSON positions). */
export function rowCount(kind, text) {
  if (kind === "csv") return text.split(/\r?\n/).filter((line) => line.trim()).length - 1;
  if (kind === "landxml") return (text.match(/<(\w+:)?Curve[\s>/]/g) || []).length;
  if (kind === "gpx") return (text.match(/<(trkpt|rtept)[\s>/]/g) || []).length;
  if (kind === "geojson") {
    try {
      return routeLines(kind, text).reduce((n, line) => n + line.length, 0);
    } catch {
      return 0;
    }
  }
  return null;
}

/** The job operation of a request path. */
const OPERATION_OF = { "/v1/alignments/assess": "alignments.assess", "/v1/routes/assess": "routes.assess" };

/** The job operation the request goes through (null: one request): above the size of one, when the deployment
 * has jobs and that operation (its POST /v1/jobs description lists them). */
export async function wantsJob(path, rows) {
  const limit = path === "/v1/routes/assess" ? settings.jobVertices : settings.jobRows;
  if (!(rows > limit) || !(await api.has("post", "/v1/jobs"))) return null;
  const operation = OPERATION_OF[path];
  if (operation === "routes.assess") {
    const doc = await api.spec();
    if (!(doc.paths["/v1/jobs"].post.description || "").includes("`routes.assess`")) return null;
  }
  return operation;
}

/**
 * An assessment as a job (`operation`: `alignments.assess` or `routes.assess`): submit, poll GET /v1/jobs/{id} (status,
 * progress, done/total) reporting each status to `onStatus`, then read its result. `key`: the bearer key (needed
 * when the deployment has keys). `signal` aborts the polling after the job was cancelled.
 */
export async function runJob(body, { operation = "alignments.assess", key, onStatus, signal }) {
  const submitted = await api.call("POST", "/v1/jobs", { json: { operation, request: body }, key });
  const location = submitted.response.headers.get("Location") || `/v1/jobs/${submitted.data.id}`;
  let job = submitted.data;
  const handle = { location, key, deleted: false };
  state.job = handle;
  // cancelled while the submission was on its way (or between two polls): the job is cancelled at the service too,
  // once (a second DELETE of a cancelled job would delete it and its status)
  const cancelled = async () => {
    if (!handle.deleted) await api.call("DELETE", location, { key }).catch(() => undefined);
    return new api.ApiError({ title: "The job was cancelled", status: 0 });
  };
  try {
    for (;;) {
      if (signal?.aborted) throw await cancelled();
      onStatus(job);
      if (job.status === "done") break;
      if (job.status === "failed" || job.status === "cancelled") {
        throw new api.ApiError(job.error || { title: `The job was ${job.status}`, status: 0 });
      }
      await new Promise((resolve) => setTimeout(resolve, 250));
      if (signal?.aborted) throw await cancelled();
      job = await api.get(location, { key });
    }
    return await api.get(job.result || `${location}/result`, { key });
  } finally {
    state.job = null;
  }
}

/** Cancel the running job (DELETE /v1/jobs/{id}). */
export async function cancelJob() {
  const job = state.job;
  if (!job || job.deleted) return;
  job.deleted = true;
  await api.call("DELETE", job.location, { key: job.key });
}

// ------------------------------------------------------------------------------------------ the table

/** The curves' columns: the curve, then what a reader acts on (flag, margin, safe and posted speed, what governs),
 * then the geometry and the speeds behind them. The first column stays in view when the table scrolls sideways. */
const COLUMNS = [
  { key: "id", label: "Curve", text: true },
  { key: "flagged", label: "Flag", format: (v) => (v ? "\u26a0 flagged" : "ok"), text: true },
  { key: "margin_kmh", label: "Margin [km/h]", format: (v) => (v === null || v === undefined ? "-" : signed(v, 1)) },
  { key: "safe_speed_kmh", label: "Safe speed [km/h]", format: (v) => fmt(v, 1) },
  { key: "posted_speed_kmh", label: "Posted [km/h]", format: (v) => fmt(v, 0) },
  { key: "governed_by", label: "Governed by", text: true },
  { key: "vehicle", label: "Vehicle", text: true },
  { key: "station_m", label: "Station [m]", format: (v) => fmt(v, 0) },
  { key: "radius_m", label: "R [m]", format: (v) => fmt(v, 0) },
  { key: "radius_std_m", label: "\u00b1 R [m] (1 s.e.)", format: (v) => fmt(v, 1) },
  { key: "direction", label: "Turns", text: true },
  { key: "superelevation_percent", label: "e [%]", format: (v) => fmt(v, 2) },
  { key: "grade_percent", label: "Grade [%]", format: (v) => fmt(v, 1) },
  { key: "srt_g", label: "SRT [g]", format: (v) => fmt(v, 3) },
  { key: "rollover_speed_kmh", label: "Rollover speed [km/h]", format: (v) => fmt(v, 1) },
  { key: "side_friction_speed_kmh", label: "Side-friction speed [km/h]", format: (v) => fmt(v, 1) },
  { key: "meets_standard_min_radius", label: "Meets Rmin", format: (v) => (v === null || v === undefined ? "-" : v ? "yes" : "no"), text: true },
  { key: "error", label: "Error", text: true },
];

/** A vehicle of a multi-vehicle answer by name: its preset id, saved id, or its place. */
export function vehicleLabel(entry, i) {
  return entry?.preset || entry?.saved_vehicle_id || `vehicle ${i + 1}`;
}

/** Whether an answer is a route's (POST /v1/routes/assess: `parts` read from the document, `curves` found on them). */
export const isRoute = (result) => Array.isArray(result.parts);

/** A route's curves: the JSON answer's list (each with its `coordinates`), or a FeatureCollection's features. */
export function routeCurves(result) {
  if (Array.isArray(result.curves)) return result.curves;
  return (result.curves?.features || []).map((f) => ({ ...f.properties, coordinates: f.geometry?.coordinates }));
}

/**
 * Rows of either answer for vehicle `index` (null: a route's governing vehicle, the one with the lowest safe speed):
 * a route's curves (the geometry, and the assessment in `assessment` or, per vehicle, `vehicles[index]`), or an
 * alignment's vehicles[index].rows.
 */
export function rowsOf(result, index = null) {
  if (isRoute(result)) {
    return routeCurves(result).map((c) => {
      const { assessment, vehicles, governing_vehicle: governing, coordinates: _xy, ...p } = c;
      const row = index === null || !vehicles ? assessment : vehicles[index];
      const vehicle = result.vehicles.length > 1 ? vehicleLabel(result.vehicles[index ?? governing], index ?? governing) : undefined;
      // the curve's own radius and grade (null without elevations) stay; the assessment adds the rest
      return { ...row, ...p, vehicle, station_m: p.start_m, grade_percent: p.grade_percent ?? row.grade_percent };
    });
  }
  return result.vehicles[index ?? 0].rows;
}

function compare(key, direction) {
  return (a, b) => {
    const x = a[key];
    const y = b[key];
    if (x === y) return 0;
    if (x === null || x === undefined) return 1; // blanks last either way
    if (y === null || y === undefined) return -1;
    const order = typeof x === "number" && typeof y === "number" ? x - y : String(x).localeCompare(String(y), undefined, { numeric: true });
    return direction === "ascending" ? order : -order;
  };
}

function renderTable(box, rows, sort) {
  const used = COLUMNS.filter((c) => rows.some((r) => r[c.key] !== undefined && r[c.key] !== null) || c.key === "flagged");
  const sorted = sort ? [...rows].sort(compare(sort.key, sort.direction)) : rows;
  const head = el(
    "tr",
    {},
    used.map((c) =>
      el(
        "th",
        { scope: "col", class: c.text ? "text" : null, "aria-sort": sort?.key === c.key ? sort.direction : "none" },
        el("button", { type: "button", class: "sort", "data-key": c.key, title: `Sort by ${c.label}` }, c.label),
      ),
    ),
  );
  const body = sorted.map((r) =>
    el("tr", { class: r.flagged ? "flagged" : null }, used.map((c) => el("td", { class: c.text ? "text" : null }, c.format ? c.format(r[c.key], r) : r[c.key] ?? "-"))),
  );
  const t = el("table", { id: "curves-table" }, el("caption", { class: "hint" }, "Select a column heading to sort."), el("thead", {}, head), el("tbody", {}, body));
  clear(box).append(scroller("Assessed curves", t, true));
  head.addEventListener("click", (ev) => {
    const button = ev.target.closest("button.sort");
    if (!button) return;
    const key = button.dataset.key;
    const direction = sort?.key === key && sort.direction === "ascending" ? "descending" : "ascending";
    renderTable(box, rows, { key, direction });
    box.querySelector(`button.sort[data-key="${key}"]`).focus();
  });
}

// ------------------------------------------------------------------------------------------ the outline

/** [[lon, lat], ...] polylines of a GeoJSON or GPX document (what the route is drawn from). */
export function routeLines(kind, text) {
  if (kind === "gpx") {
    const doc = new DOMParser().parseFromString(text, "application/xml");
    const lines = [];
    for (const seg of doc.querySelectorAll("trkseg, rte")) {
      const pts = Array.from(seg.querySelectorAll("trkpt, rtept")).map((p) => [Number(p.getAttribute("lon")), Number(p.getAttribute("lat"))]);
      if (pts.length > 1) lines.push(pts);
    }
    return lines;
  }
  const geo = JSON.parse(text);
  const lines = [];
  const visit = (g) => {
    if (!g) return;
    if (g.type === "FeatureCollection") g.features.forEach((f) => visit(f.geometry));
    else if (g.type === "Feature") visit(g.geometry);
    else if (g.type === "LineString") lines.push(g.coordinates);
    else if (g.type === "MultiLineString") lines.push(...g.coordinates);
  };
  visit(geo);
  return lines;
}

/** Chainage [m] along a lon/lat polyline (equirectangular, adequate for locating curves on a sketch). */
function chainage(points) {
  const out = [0];
  for (let i = 1; i < points.length; i += 1) {
    const [x0, y0] = points[i - 1];
    const [x1, y1] = points[i];
    const k = Math.cos(((y0 + y1) / 2) * (Math.PI / 180));
    const dx = (x1 - x0) * k * 111_320;
    const dy = (y1 - y0) * 110_574;
    out.push(out[i - 1] + Math.hypot(dx, dy));
  }
  return out;
}

function slice(points, s, start, end) {
  return points.filter((_, i) => s[i] >= start && s[i] <= end);
}

/** A simple SVG outline of the route with the curves drawn over it, flagged ones in red. */
export function outline(lines, result) {
  const all = lines.flat();
  if (!all.length) return null;
  const lat0 = all.reduce((a, p) => a + p[1], 0) / all.length;
  const k = Math.cos(lat0 * (Math.PI / 180));
  const xy = ([lon, lat]) => [lon * k, -lat];
  const pts = all.map(xy);
  let [minX, maxX, minY, maxY] = [Infinity, -Infinity, Infinity, -Infinity]; // no spread: long routes
  for (const [x, y] of pts) {
    minX = Math.min(minX, x);
    maxX = Math.max(maxX, x);
    minY = Math.min(minY, y);
    maxY = Math.max(maxY, y);
  }
  const span = Math.max(maxX - minX, maxY - minY) || 1e-6;
  const pad = span * 0.04;
  const svg = svgEl("svg", {
    viewBox: `${minX - pad} ${minY - pad} ${maxX - minX + 2 * pad} ${maxY - minY + 2 * pad}`,
    role: "img",
    "aria-label": "Route outline; the assessed curves are drawn over it, flagged curves in red",
    preserveAspectRatio: "xMidYMid meet",
  });
  const path = (points, cls, title) => {
    const p = svgEl("polyline", { class: cls, points: points.map((q) => xy(q).join(",")).join(" ") });
    if (title) p.append(Object.assign(svgEl("title"), { textContent: title }));
    svg.append(p);
  };
  for (const line of lines) path(line, "route");
  const main = lines[0];
  const s = chainage(main);
  for (const p of routeCurves(result)) {
    const flagged = Boolean(p.assessment?.flagged);
    let points = null;
    if (Array.isArray(p.coordinates)) points = p.coordinates;
    else if (typeof p.start_m === "number" && typeof p.end_m === "number") points = slice(main, s, p.start_m, p.end_m);
    if (points && points.length > 1) {
      path(points, flagged ? "curve flagged" : "curve", `Curve ${p.id ?? ""}: R ${fmt(p.radius_m, 0)} m${flagged ? ", flagged" : ""}`);
    }
  }
  return svg;
}

// ------------------------------------------------------------------------------------------ render

function summaryLine(result, index) {
  const several = result.vehicles.length > 1;
  if (index === null && several) {
    // a fleet's route, each curve by its governing vehicle
    const flagged = state.rows.filter((r) => r.flagged).length;
    return `${state.rows.length} curves, ${flagged} flagged for their governing vehicle; ${result.vehicles.length} vehicles, route ${fmt(result.length_m / 1000, 2)} km`;
  }
  const s = result.vehicles[index ?? 0].summary;
  const parts = [`${s.curves} curves`, `${s.flagged} flagged`];
  if (several) parts.push(`for ${vehicleLabel(result.vehicles[index], index)}`);
  if (typeof result.length_m === "number") parts.push(`route ${fmt(result.length_m / 1000, 2)} km`);
  if (s.below_standard_min_radius) parts.push(`${s.below_standard_min_radius} below the standard's minimum radius`);
  if (s.refused) parts.push(`${s.refused} refused`);
  if (s.min_margin_kmh !== undefined && s.min_margin_kmh !== null) parts.push(`smallest margin ${signed(s.min_margin_kmh, 1)} km/h`);
  if (s.min_safe_speed_kmh !== undefined && s.min_safe_speed_kmh !== null) parts.push(`lowest safe speed ${fmt(s.min_safe_speed_kmh, 1)} km/h`);
  return parts.join(", ");
}

/** The vehicle choice of a multi-vehicle answer (a fleet): a route adds "the governing vehicle of each curve". */
function vehicleChoice(result, route, onChange) {
  const options = result.vehicles.map((v, i) => el("option", { value: String(i) }, vehicleLabel(v, i)));
  if (route) options.unshift(el("option", { value: "" }, "the governing vehicle of each curve (lowest safe speed)"));
  const select = el("select", { id: "al-vehicle-shown" }, options);
  select.addEventListener("change", () => onChange(select.value === "" ? null : Number(select.value)));
  return el("div", { class: "field" }, el("label", { for: "al-vehicle-shown" }, "Vehicle shown"), select);
}

export function render(result, kind, lines) {
  const route = kind === "geojson" || kind === "gpx";
  state.result = result;
  state.kind = kind;
  const box = clear($("#alignment-results"));
  const summary = el("p", { id: "alignment-summary" });
  const tableBox = el("div");
  const show = (index) => {
    state.rows = rowsOf(result, index);
    summary.textContent = `${summaryLine(result, index)}.`;
    renderTable(tableBox, state.rows, null);
  };
  if (result.vehicles.length > 1) box.append(vehicleChoice(result, route, show));
  box.append(summary);
  state.outline = lines ? outline(lines, result) : null;
  if (state.outline) box.append(el("figure", { class: "outline" }, state.outline, el("figcaption", { class: "hint" }, "Route outline (north up); flagged curves in red.")));
  const downloads = el("div", { class: "actions" });
  downloads.append(
    el("button", { type: "button", id: "download-csv", onclick: downloadCsv }, "Download CSV"),
    el("button", { type: "button", id: "download-json", onclick: () => save("json") }, route ? "Download GeoJSON" : "Download JSON"),
  );
  box.append(downloads, tableBox);
  show(route ? null : 0);
}

async function downloadCsv() {
  const { path, request, key } = state;
  const { data } = await api.call("POST", path, { json: request, accept: "text/csv", as: "blob", key });
  download("curves.csv", data);
}

/** The JSON answer; a route's curves as GeoJSON (the same request with Accept: application/geo+json). */
async function save() {
  const { path, request, key, result } = state;
  if (isRoute(result)) {
    const { data } = await api.call("POST", path, { json: request, accept: "application/geo+json", as: "blob", key });
    download("curves.geojson", data);
  } else {
    download("assessment.json", new Blob([JSON.stringify(result, null, 1)], { type: "application/json" }));
  }
}

/** The curves for the printout: the summary line, the outline and the table, at most `max` rows (flagged first). */
export function printable(max = 60) {
  const t = $("#curves-table")?.cloneNode(true);
  if (!t) return null;
  const rows = Array.from(t.tBodies[0].rows);
  let note = null;
  if (rows.length > max) {
    const keep = [...rows.filter((r) => r.classList.contains("flagged")), ...rows.filter((r) => !r.classList.contains("flagged"))].slice(0, max);
    for (const r of rows) if (!keep.includes(r)) r.remove();
    note = el("p", { class: "hint" }, `${max} of ${rows.length} curves printed (the flagged ones first); the CSV download has them all.`);
  }
  t.querySelector("caption")?.remove();
  for (const b of t.querySelectorAll("button.sort")) b.replaceWith(document.createTextNode(b.textContent));
  return [$("#alignment-summary"), $("#alignment-results figure.outline"), note, t];
}
