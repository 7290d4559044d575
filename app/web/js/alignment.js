// Section 5: an alignment (CSV or LandXML: POST /v1/alignments/assess with the file's text, so any vehicle --
// preset, saved, built or pasted -- can be assessed) or a route (GeoJSON or GPX: POST /v1/routes/assess, when
// the deployment has it). A sortable table of the curves with their flags, the route's outline as an SVG with
// the flagged curves marked (no map tiles: the page works offline), a progress bar (POST /v1/jobs when the
// deployment has it, otherwise an indeterminate bar while the request runs) and downloads.

import * as api from "./api.js";
import * as curves from "./curves.js";
import { $, clear, download, el, fmt, num, svgEl, svgNode } from "./dom.js";
import { value } from "./form.js";
import { designFields, srtOptions } from "./road.js";
import { showWarnings } from "./results.js";

export const state = { result: null, request: null, path: null, key: undefined, kind: null, rows: [], outline: null, job: null };

const drop = (obj) => Object.fromEntries(Object.entries(obj).filter(([, v]) => v !== undefined));

/** csv | landxml | ifc | geojson | gpx, from the file's name and, failing that, its first characters. */
export function formatOf(name, text) {
  const ext = (name.split(".").pop() || "").toLowerCase();
  if (ext === "csv") return "csv";
  if (ext === "ifc") return "ifc";
  if (ext === "gpx") return "gpx";
  if (ext === "geojson" || ext === "json") return "geojson";
  if (ext === "xml" || ext === "landxml") return /<gpx[\s>]/.test(text.slice(0, 2000)) ? "gpx" : "landxml";
  const head = text.trimStart();
  if (head.startsWith("ISO-10303-21")) return "ifc"; // an IFC file's STEP header (ISO 10303-21)
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
    // the truck's speed profile and the plaques (docs/advisory.md): only what was typed
    desired_speed_kmh: value($("#al-desired")),
    deceleration_mps2: value($("#al-decel")),
    units: $("#al-units").value || undefined,
  });
  if (kind === "csv") return ["/v1/alignments/assess", { ...common, csv: text }];
  if (kind === "landxml" || kind === "ifc") {
    // an IFC 4.3 file takes the same fields as a LandXML one (`ifc`, docs/uploads.md "IFC 4.3")
    const file = drop({
      document: text,
      superelevation_percent: value($("#al-e")),
      grade_percent: value($("#al-grade")),
      posted_speed_kmh: value($("#al-posted")),
    });
    return ["/v1/alignments/assess", { ...common, [kind]: file }];
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

/** The lines of a text that hold more than blanks (counted without splitting it: a file can hold a million). */
function csvLines(text) {
  let count = 0;
  let start = 0;
  while (start < text.length) {
    let end = text.indexOf("\n", start);
    if (end < 0) end = text.length;
    for (let i = start; i < end; i += 1) {
      const c = text.charCodeAt(i);
      if (c !== 32 && c !== 9 && c !== 13) {
        count += 1;
        break;
      }
    }
    start = end + 1;
  }
  return count;
}

/** The curves of an alignment file (CSV data rows, LandXML <Curve> elements, IFC circular-arc segments); a route's vertices (GPX points,
 * GeoJSON positions). */
export function rowCount(kind, text) {
  if (kind === "csv") return csvLines(text) - 1;
  if (kind === "landxml") return (text.match(/<(\w+:)?Curve[\s>/]/g) || []).length;
  if (kind === "ifc") return (text.match(/IFCALIGNMENTHORIZONTALSEGMENT\([^;]*\.CIRCULARARC\./gi) || []).length;
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
 * when the deployment has keys). `signal` aborts the polling after the job was cancelled. `read`: false answers the
 * result's URL instead of the result (a large result is read by the curves' worker, not on the page).
 */
export async function runJob(body, { operation = "alignments.assess", key, onStatus, signal, read = true }) {
  // the body (a file of a million curves is a hundred megabytes of JSON) is written by the curves' worker, not here
  const { blob } = await curves.ask("encode", { value: { operation, request: body } });
  const submitted = await api.call("POST", "/v1/jobs", { json: blob, key });
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
    const url = job.result || `${location}/result`;
    return read ? await api.get(url, { key }) : url;
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

// ------------------------------------------------------------------------------------------ the rows

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

// ------------------------------------------------------------------------------------------ what was read

/** A file's length unit in words, by its name with case, spaces, '-', '_' and '.' removed (the names LandXML
 * `linearUnit` takes, docs/uploads.md Units, and those IFC names, app/formats/ifc_io.py `_NAMED_LENGTH`, SI metres
 * with a prefix); every length is converted to metres before it is assessed. */
const CONVERTED = "every length converted to metres";
const UNIT_WORDS = {
  meter: "metres",
  metre: "metres",
  kilometer: "kilometres",
  kilometre: "kilometres",
  centimeter: "centimetres",
  centimetre: "centimetres",
  millimeter: "millimetres",
  millimetre: "millimetres",
  foot: `feet (international foot, 0.3048 m): ${CONVERTED}`,
  feet: `feet (international foot, 0.3048 m): ${CONVERTED}`,
  ft: `feet (international foot, 0.3048 m): ${CONVERTED}`,
  internationalfoot: `feet (international foot, 0.3048 m): ${CONVERTED}`,
  ussurveyfoot: `US survey feet (1200/3937 m): ${CONVERTED}`,
  ussurveyfeet: `US survey feet (1200/3937 m): ${CONVERTED}`,
  surveyfoot: `US survey feet (1200/3937 m): ${CONVERTED}`,
  usfoot: `US survey feet (1200/3937 m): ${CONVERTED}`,
  inch: `inches (0.0254 m): ${CONVERTED}`,
  inches: `inches (0.0254 m): ${CONVERTED}`,
  yard: `yards (0.9144 m): ${CONVERTED}`,
  mile: `miles (1609.344 m): ${CONVERTED}`,
};
const unitWords = (name) => UNIT_WORDS[String(name).toLowerCase().replace(/[\s\-_.]/g, "")] || `${name} (as the file names it): ${CONVERTED}`;

/** `reading.superelevation_from` in words (docs/uploads.md and docs/routes.md, `superelevation_from`). */
const SUPERELEVATION_WORDS = {
  file: "the file (its superelevation elements or properties)",
  "cross-sections": "the file's cross sections (their cross slopes)",
  request: "the superelevation typed in this form",
  standard: "the standard's design rule, from the maximum superelevation typed in this form",
};

/** Above this many skipped items the list is folded (a click opens it); on paper it is always open. */
const SKIPPED_OPEN = 5;

/**
 * The "Read from the file" panel of an answer's `reading` (format, writer, unit, alignments, elements, profile,
 * superelevation's source, what the reader assumed, skipped parts with why). `print`: the printout's copy (the
 * skipped list never folded).
 */
export function readingPanel(reading, { print = false } = {}) {
  const unit = unitWords(reading.linear_unit);
  const elements = Object.entries(reading.elements || {}).map(([type, n]) => `${type} ${fmt(n, 0)}`).join(", ");
  const from = reading.superelevation_from;
  const facts = [
    ["Format", reading.format],
    ["Written by", reading.writer || "not named in the file"],
    ["Length unit", unit],
    [reading.alignments.length === 1 ? "Alignment read" : `Alignments read (${reading.alignments.length})`, reading.alignments.join("; ") || "none"],
    ["Elements read", elements || "none"],
    ["Profile used", reading.profile || "none (no grades read from the file)"],
    ["Superelevation from", from ? SUPERELEVATION_WORDS[from] || from : "none (no curves)"],
  ];
  // what the reader assumed where the file is silent (a start station of 0, names in raw UTF-8): never folded
  const notes = reading.notes || [];
  const assumed = notes.length
    ? [el("p", { class: "notes-head" }, "Assumed where the file is silent:"), el("ul", { class: "notes" }, notes.map((n) => el("li", {}, n)))]
    : [];
  const skipped = reading.skipped || [];
  const items = el("ul", { class: "skipped" }, skipped.map((s) => el("li", {}, el("strong", {}, s.what), `: ${s.why}`)));
  let rest;
  if (!skipped.length) rest = el("p", { class: "skipped-none" }, "Nothing in the file was skipped.");
  else if (print || skipped.length <= SKIPPED_OPEN) rest = [el("p", { class: "skipped-head" }, `Skipped (${skipped.length}), and why:`), items];
  else rest = el("details", {}, el("summary", {}, `Skipped (${skipped.length}), and why`), items);
  return el(
    "section",
    { class: `reading${print ? " keep" : ""}`, "aria-label": "Read from the file" },
    el(print ? "h4" : "h3", { class: "reading-title" }, "Read from the file"),
    el("dl", { class: "facts" }, facts.flatMap(([k, v]) => [el("dt", {}, k), el("dd", {}, v)])),
    ...assumed,
    rest,
  );
}

// ------------------------------------------------------------------------------------------ render

/** The speed profile's inputs in words (the answer's `advisory`; the defaults as docs/advisory.md states them). */
function profileBasis(adv) {
  const decel = adv?.deceleration_mps2;
  // a curve's posted speed is its tangent's; the desired speed, when given, only where a curve has none
  const desired = typeof adv?.desired_speed_kmh === "number" ? `each curve's posted speed, ${fmt(adv.desired_speed_kmh, 0)} km/h where a curve has none` : "each curve's posted speed";
  const braking = typeof decel === "number" ? `${num(decel, 3)} m/s\u00b2 (${num(decel / 0.3048, 1)} ft/s\u00b2)` : "the service's default";
  return (
    `It depends on the truck's desired speed on the tangents (${desired}), the braking rate into each curve (${braking}; ` +
    "the default 10 ft/s\u00b2 and the 2.5 s reaction time are MUTCD 11e Table 2C-3's basis as transcribed: unverified) " +
    "and the acceleration out of it within the truck's power (120 kg/kW, the HCM truck; the resistances assumed). " +
    "The speed never exceeds a curve's safe or advisory speed."
  );
}

/**
 * The truck's speed profile along an alignment (POST /v1/plots/speed-profile with the assessment's request): the
 * plot with what it depends on, or in words why there is none. The service plots an alignment's request only: a
 * route's profile is drawn here from its answer; a job's request is not sent twice, so its figure says where the
 * profile is.
 */
async function speedProfile({ result, job, route, head }) {
  if (!head?.advisory || !(await api.has("post", "/v1/plots/speed-profile"))) return null;
  const box = el("figure", { class: "plot speed-profile keep", id: "speed-profile" });
  const caption = el("figcaption", {}, el("strong", {}, "The truck's speed profile. "), profileBasis(head.advisory));
  const notes = (result?.vehicles || []).flatMap((v) => v.speed_profile_notes || []);
  if (job) {
    box.append(el("p", { class: "hint" }, "A job's speed profile (its stations and speeds) is in its JSON result (speed_profile); the plot is drawn for a road assessed in one request."), caption);
    return box;
  }
  if (route) {
    // the service plots an alignment's request only: a route's profile is drawn here from its answer
    const drawn = routeProfile(result);
    box.append(drawn || el("p", { class: "no-profile" }, "No speed profile: the curves' stations or tangent speeds cannot carry one (each curve's row says why)."), caption);
    if (notes.length) box.append(el("ul", { class: "hint" }, [...new Set(notes)].map((n) => el("li", {}, n))));
    return box;
  }
  try {
    const { data } = await api.call("POST", "/v1/plots/speed-profile", { json: state.request, accept: "image/svg+xml", key: state.key });
    box.append(svgNode(data), caption);
  } catch (err) {
    if (!(err instanceof api.ApiError)) throw err;
    box.append(el("p", { class: "no-profile" }, `No speed profile: ${err.problem.detail || err.problem.title}.`), caption);
  }
  if (notes.length) box.append(el("ul", { class: "hint" }, [...new Set(notes)].map((n) => el("li", {}, n))));
  return box;
}

/**
 * A route's speed profile drawn from its answer (the first vehicle's `speed_profile`, each curve's safe and advisory
 * speed over its chainage, its posted speed): speed [km/h] against chainage [km], as the service's alignment plot
 * shows them. Null when there is no profile.
 */
export function routeProfile(result) {
  const vehicle = result.vehicles?.[0];
  const points = vehicle?.speed_profile || [];
  if (points.length < 2) return null;
  const spans = routeCurves(result).map((c) => ({ start: c.start_m, end: c.end_m, row: c.vehicles ? c.vehicles[0] : c.assessment }));
  const speeds = [
    ...points.map((p) => p.speed_kmh),
    ...spans.flatMap((c) => [c.row?.safe_speed_kmh, c.row?.advisory_speed_kmh, c.row?.posted_speed_kmh]),
  ].filter((v) => typeof v === "number" && Number.isFinite(v));
  const x0 = Math.min(points[0].station_m, ...spans.map((c) => c.start).filter(Number.isFinite));
  const x1 = Math.max(points.at(-1).station_m, ...spans.map((c) => c.end).filter(Number.isFinite));
  const top = Math.ceil(Math.max(...speeds) / 10) * 10 + 10;
  const [w, h, left, right, up, down] = [760, 400, 56, 190, 28, 44];
  const X = (m) => left + ((m - x0) / (x1 - x0 || 1)) * (w - left - right);
  const Y = (v) => h - down - (v / top) * (h - up - down);
  const svg = svgEl("svg", { viewBox: `0 0 ${w} ${h}`, role: "img", "aria-label": "Truck speed profile against chainage (route)", "font-family": "Helvetica, Arial, sans-serif", "font-size": "12" });
  const text = (x, y, t, anchor = "middle") => {
    const n = svgEl("text", { x, y, "text-anchor": anchor });
    n.textContent = t;
    svg.append(n);
  };
  svg.append(svgEl("rect", { width: w, height: h, fill: "white" }));
  for (let v = 0; v <= top; v += top > 80 ? 20 : 10) {
    svg.append(svgEl("line", { x1: left, x2: w - right, y1: Y(v), y2: Y(v), stroke: "#dddddd" }));
    text(left - 6, Y(v) + 4, String(v), "end");
  }
  const step = Math.max(0.1, Number((10 ** Math.floor(Math.log10((x1 - x0) / 1000 || 1))).toPrecision(1)));
  for (let k = Math.ceil(x0 / 1000 / step) * step; k <= x1 / 1000 + 1e-9; k += step) {
    svg.append(svgEl("line", { x1: X(k * 1000), x2: X(k * 1000), y1: up, y2: h - down, stroke: "#eeeeee" }));
    text(X(k * 1000), h - down + 16, num(k, 2));
  }
  text((left + w - right) / 2, h - 8, "chainage [km]");
  text(14, up - 10, "speed [km/h]", "start");
  const segment = (c, v, colour, dash) => {
    if (typeof v !== "number" || !Number.isFinite(c.start) || !Number.isFinite(c.end)) return;
    svg.append(svgEl("line", { x1: X(c.start), x2: X(c.end), y1: Y(v), y2: Y(v), stroke: colour, "stroke-width": 3, ...(dash ? { "stroke-dasharray": dash } : {}) }));
  };
  for (const c of spans) {
    segment(c, c.row?.posted_speed_kmh, "#2e7d32", "6 4");
    segment(c, c.row?.safe_speed_kmh, "#c62828");
    segment(c, c.row?.advisory_speed_kmh, "#ef6c00");
  }
  svg.append(svgEl("polyline", { points: points.map((p) => `${X(p.station_m)},${Y(p.speed_kmh)}`).join(" "), fill: "none", stroke: "#1565c0", "stroke-width": 2 }));
  const legend = [
    ["#1565c0", "truck's speed profile", null],
    ["#c62828", "safe speed of each curve", null],
    ["#ef6c00", "advisory speed (plaque)", null],
    ["#2e7d32", "posted speed", "6 4"],
  ];
  legend.forEach(([colour, label, dash], i) => {
    const y = up + 14 + i * 20;
    svg.append(svgEl("line", { x1: w - right + 12, x2: w - right + 36, y1: y - 4, y2: y - 4, stroke: colour, "stroke-width": 3, ...(dash ? { "stroke-dasharray": dash } : {}) }));
    text(w - right + 42, y, label, "start");
  });
  const name = vehicleLabel(vehicle, 0);
  text((left + w - right) / 2, 16, `Truck speed profile along the route: ${name}`);
  return svg;
}

/** A fleet's vehicle choice: each vehicle, and for a route "the governing vehicle of each curve". */
function vehicleChoice(names, route, onChange) {
  const options = names.map((name, i) => el("option", { value: String(i) }, name));
  if (route) options.unshift(el("option", { value: "" }, "the governing vehicle of each curve (lowest safe speed)"));
  const select = el("select", { id: "al-vehicle-shown" }, options);
  select.addEventListener("change", () => onChange(select.value === "" ? null : Number(select.value)));
  return el("div", { class: "field" }, el("label", { for: "al-vehicle-shown" }, "Vehicle shown"), select);
}

/** The vehicles of a job's CSV rows (their index, preset or saved id), from the worker's counts. */
const csvVehicles = (stats) => stats.vehicles || [];

/**
 * Show an assessment: `result` (the JSON answer) or, for an alignment job, `job` {url, key} (its result is read as
 * CSV by the worker, never parsed on the page); `stored` {url, key}: where a route job's result is kept (for the
 * downloads). `kind`: csv, landxml, ifc, geojson or gpx; `lines`: a route's polylines;
 * `fileName` and `vehicleText` name the file and the vehicle on paper. Resolves once the first page of rows is drawn
 * and the printout is built.
 */
export async function render({ result = null, job = null, stored = null, kind, lines = null, fileName = "", vehicleText = "" }) {
  const route = kind === "geojson" || kind === "gpx";
  // a job's result stays at the service: the downloads read it from there (a job is above the synchronous size)
  Object.assign(state, { result, kind, file: fileName, vehicleText, jobResult: job || stored });
  const box = clear($("#alignment-results"));
  const summary = el("p", { id: "alignment-summary" });
  const tableBox = el("div", { id: "curves-box" });
  let names;
  let loaded = null;
  let head = result;
  if (job) {
    // the rows as CSV (the table's), and the head of the JSON result for what the CSV lacks: what was read from the
    // file and the plaques' options (its first bytes only: the worker stops reading at the rows)
    let top;
    [loaded, top] = await Promise.all([
      curves.ask("fetch", { url: job.url, key: job.key, vehicle: 0 }),
      curves.ask("head", { url: job.url, key: job.key }).catch(() => ({ head: null })),
    ]);
    head = top.head;
    names = csvVehicles(loaded.stats).map((v, i) => vehicleLabel(v, i));
  } else {
    names = result.vehicles.map((v, i) => vehicleLabel(v, i));
  }
  const several = names.length > 1;
  curves.advisory.units = head?.advisory?.units ?? null;
  curves.advisory.increment = head?.advisory?.increment ?? null;
  const signs = el("div", { id: "alignment-signs" });
  const show = async (index) => {
    let stats;
    if (job) stats = (await curves.ask("stats", { vehicle: index })).stats;
    else stats = (await curves.ask("load", { rows: rowsOf(result, index), vehicle: null })).stats;
    const vehicleText = several ? (index === null ? `${names.length} vehicles` : `for ${names[index]}`) : "";
    const lengthM = result?.length_m;
    const governing = several && index === null;
    summary.textContent = curves.summaryText(stats, { vehicleText, lengthM, governing });
    clear(signs);
    if (stats.advised) signs.append(curves.signsNotes(stats, head?.advisory));
    await curves.showTable(tableBox, { keys: stats.keys, vehicle: job ? index : null });
    const printed = await curves.printout({
      stats,
      fileName,
      vehicleText: several ? (index === null ? `the governing vehicle of each curve, of ${names.join(", ")}` : names[index]) : state.vehicleText,
      lengthM,
      governing,
      outline: state.outline,
      downloadName: state.file ? `${state.file.replace(/\.[^.]*$/, "")}-curves.csv` : "curves.csv",
    });
    // what was read, on the road's first printed page right after its summary
    if (head?.reading) printed.splice(1, 0, readingPanel(head.reading, { print: true }));
    // the speed profile, after the outline and before the curves
    const plot = $("#speed-profile");
    if (plot) printed.splice(printed.findIndex((n) => n?.tagName === "H4"), 0, plot.cloneNode(true));
    document.dispatchEvent(new CustomEvent("curves-printout", { detail: { title: route ? "Route" : "Alignment", nodes: printed } }));
  };
  if (head?.reading) box.append(readingPanel(head.reading));
  if (several) box.append(vehicleChoice(names, route, show));
  box.append(summary, signs);
  // typed values that read plausibly in another unit too, every vehicle's, in the service's words (a job's CSV
  // rows carry none: its JSON result has them)
  const warnings = (result?.vehicles || []).flatMap((v) => v.warnings || []);
  if (warnings.length) {
    const warned = el("div", { id: "alignment-warnings", class: "input-warnings", role: "note" },
      el("p", {}, el("strong", {}, "Check these inputs:"), " each was answered as typed, but reads plausibly in another unit too."),
      el("ul"));
    showWarnings(warned, warnings);
    box.append(warned);
  }
  const profile = await speedProfile({ result, job, route, head });
  if (profile) box.append(profile);
  state.outline = lines && result ? outline(lines, result) : null;
  if (state.outline) box.append(el("figure", { class: "outline" }, state.outline, el("figcaption", { class: "hint" }, "Route outline (north up); flagged curves in red.")));
  const downloads = el("div", { class: "actions" });
  downloads.append(
    el("button", { type: "button", id: "download-csv", onclick: downloadCsv }, "Download CSV (every curve)"),
    el("button", { type: "button", id: "download-json", onclick: save }, route ? "Download GeoJSON (every curve)" : "Download JSON (every curve)"),
  );
  box.append(downloads, tableBox);
  await show(route ? null : 0);
}

/** The file name of a download: the assessed file's with what it holds. */
const downloadName = (suffix) => `${(state.file || "curves").replace(/\.[^.]*$/, "")}-${suffix}`;

/** The whole result as CSV: a job's result again (Accept: text/csv), else the same request with Accept: text/csv. */
async function downloadCsv() {
  const { path, request, key, jobResult } = state;
  const { data } = jobResult
    ? await api.call("GET", jobResult.url, { accept: "text/csv", as: "blob", key: jobResult.key })
    : await api.call("POST", path, { json: request, accept: "text/csv", as: "blob", key });
  download(downloadName("curves.csv"), data);
}

/** A route's curves as GeoJSON (the same request with Accept: application/geo+json); an alignment's JSON answer
 * (a job's: its result as stored, never parsed here). */
async function save() {
  const { path, request, key, result, jobResult } = state;
  if (jobResult && result && isRoute(result)) {
    // a route job's answer is in hand: its curves as the service's GeoJSON writes them (each curve's fields as the
    // properties, its coordinates as the LineString), since the synchronous request is above its size
    const features = routeCurves(result).map(({ coordinates, ...properties }) => ({ type: "Feature", geometry: { type: "LineString", coordinates }, properties }));
    // with the foreign members the service's GeoJSON carries (RFC 7946 section 6.1: `reading`, `advisory`, and
    // `warnings`: every vehicle's input warnings in vehicle order, app/routes/service.py route_geojson)
    const members = Object.fromEntries(["reading", "advisory"].filter((k) => result[k] !== undefined).map((k) => [k, result[k]]));
    members.warnings = (result.vehicles || []).flatMap((v) => v.warnings || []);
    const collection = { type: "FeatureCollection", features, ...members };
    download(downloadName("curves.geojson"), new Blob([JSON.stringify(collection)], { type: "application/geo+json" }));
  } else if (jobResult) {
    const { data } = await api.call("GET", jobResult.url, { accept: "application/json", as: "blob", key: jobResult.key });
    download(downloadName("assessment.json"), data);
  } else if (isRoute(result)) {
    const { data } = await api.call("POST", path, { json: request, accept: "application/geo+json", as: "blob", key });
    download(downloadName("curves.geojson"), data);
  } else {
    download(downloadName("assessment.json"), new Blob([JSON.stringify(result, null, 1)], { type: "application/json" }));
  }
}
