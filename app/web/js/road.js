// Section 4: road design. The minimum radius against design speed (Eq. 9.2 with the standard's side friction
// against the vehicle's Eq. 9.3: POST /v1/plots/min-radius and /v1/min-radius), the curve speed for a radius
// (POST /v1/curve-speed, Eq. 9.1), a curve's design superelevation (POST /v1/superelevation) and the acceptable
// load height by overweight (POST /v1/srt/limits).

import * as api from "./api.js";
import { $, clear, download, el, fmt, grouped, num, scroller, svgNode, table } from "./dom.js";
import { value } from "./form.js";
import { srtText } from "./results.js";

export const state = { standards: null, design: null, speed: null, advisory: null };

const drop = (obj) => Object.fromEntries(Object.entries(obj).filter(([, v]) => v !== undefined));

export function fillStandards(list) {
  state.standards = list;
  const select = clear($("#standard"));
  for (const s of list.standards) select.append(el("option", { value: s.id }, s.title));
  const pending = select.dataset.pending;
  select.value = pending && list.standards.some((s) => s.id === pending) ? pending : list.default;
  select.dataset.initial = list.default;
  describeStandard();
}

export function standard() {
  return state.standards?.standards.find((s) => s.id === $("#standard").value) || null;
}

export function describeStandard() {
  const s = standard();
  $("#bound-field").hidden = !s?.side_friction_bounds;
  $("#bound").disabled = !s?.side_friction_bounds;
  if (!s) return;
  $("#standard-citation").textContent = `${s.citation} Design speeds ${s.speed_range_kmh[0]}-${s.speed_range_kmh[1]} km/h.`;
  $("#vmin").placeholder = String(s.speed_range_kmh[0]);
  $("#vmax").placeholder = String(s.speed_range_kmh[1]);
}

/** design_standard (+ side_friction_bound for thesis-table21) */
export function designFields() {
  return drop({ design_standard: $("#standard").value || undefined, side_friction_bound: value($("#bound")) });
}

/** The SRT options of a case request (no road, no targets): what the plot and alignment requests take. */
export function srtOptions(caseRequest) {
  const { road: _road, targets: _targets, ...rest } = caseRequest;
  return rest;
}

/** The speeds of the table: the standard's tabulated design speeds inside the chosen range. */
function tableSpeeds(lo, hi) {
  const s = standard();
  const speeds = (s ? s.speeds_kmh : []).filter((v) => v >= lo && v <= hi);
  for (const v of [lo, hi]) if (!speeds.includes(v)) speeds.push(v);
  return speeds.sort((a, b) => a - b);
}

/** Minimum radius against design speed: the plot and the table. Returns the state for the summary. */
export async function minRadius(vehicleRef, caseRequest) {
  const s = standard();
  const e = value($("#road-e"));
  const vmin = value($("#vmin"));
  const vmax = value($("#vmax"));
  const design = designFields();
  const plotRequest = drop({
    vehicle: vehicleRef,
    ...srtOptions(caseRequest),
    ...design,
    superelevation_percent: e,
    slope_percent: caseRequest.road?.slope_percent,
    speed_min_kmh: vmin,
    speed_max_kmh: vmax,
  });
  const svgText = await api.postSvg("/v1/plots/min-radius", plotRequest); // refuses a bad range at its field
  // the plot accepted the range: the table covers the same one (the standard's whole range by default)
  const lo = typeof vmin === "number" ? vmin : s.speed_range_kmh[0];
  const hi = typeof vmax === "number" ? vmax : s.speed_range_kmh[1];
  const base = drop({
    vehicle: vehicleRef,
    ...srtOptions(caseRequest),
    road: drop({ slope_percent: caseRequest.road?.slope_percent }),
    targets: caseRequest.targets,
    ...design,
    superelevation_percent: e,
  });
  const rows = await Promise.all(tableSpeeds(lo, hi).map((v) => api.post("/v1/min-radius", { ...base, design_speed_kmh: v })));
  state.design = { svgText, rows, standard: s, superelevation: e };
  render(state.design);
  return state.design;
}

/** The minimum radius by design speed: the speed, then the governing radius and what governs it (the columns a
 * designer reads), then Eq. 9.2 and Eq. 9.3 and the side friction. Radii in whole metres. */
export function radiusTable(rows) {
  return table(
    [
      { key: "design_speed_kmh", label: "V [km/h]", format: (v) => fmt(v, 0) },
      { key: "governing_min_radius_m", label: "Governing R [m]", format: (v) => fmt(v, 0) },
      { key: "governed_by", label: "Governed by", nowrap: true, format: (v) => (v === "side-friction" ? "side friction" : v) },
      { key: "side_friction_min_radius_m", label: "Eq. 9.2 R [m]", format: (v) => fmt(v, 0) },
      { key: "rollover_min_radius_m", label: "Eq. 9.3 R [m]", format: (v) => fmt(v, 0) },
      { key: "side_friction", label: "Side friction f", format: (v) => fmt(v, 3) },
    ],
    rows,
    { caption: "Minimum radius by design speed: the governing one, Eq. 9.2 (side friction, f of the standard) and Eq. 9.3 (rollover)." },
  );
}

export function radiusCaption(design) {
  const srt = design.rows[0]?.srt;
  return `${design.standard ? design.standard.title : ""}; superelevation ${design.superelevation} %; the vehicle's SRT on this bank: ${srtText(srt)}.`;
}

function render(design) {
  const box = clear($("#road-results"));
  const fig = el("figure", { class: "plot" }, el("figcaption", {}, "Minimum radius against design speed: Eq. 9.2 against Eq. 9.3 (thesis Figs. 108-114)"));
  fig.prepend(svgNode(design.svgText));
  box.append(
    el("p", {}, radiusCaption(design)),
    el("div", { class: "plot-and-table" }, fig, scroller("Minimum radius by design speed", radiusTable(design.rows))),
  );
}

/** "with bank 4 % and grade 0 %": the case's road, as a computed line names it. */
export function bankWords(caseRequest) {
  const bank = caseRequest.road?.bank_percent ?? 0;
  const grade = caseRequest.road?.slope_percent ?? 0;
  return `with bank (superelevation) ${num(bank, 2)} % and grade ${num(grade, 2)} %`;
}

export async function curveSpeed(vehicleRef, caseRequest) {
  const radius = value($("#radius"));
  if (radius === undefined) {
    state.speed = null;
    $("#speed-result").textContent = "";
    return null;
  }
  const out = await api.post("/v1/curve-speed", { vehicle: vehicleRef, ...caseRequest, radius_m: radius });
  state.speed = out;
  $("#speed-result").textContent = `On a curve of radius ${grouped(out.radius_m, 0)} m ${bankWords(caseRequest)}: at most ${fmt(out.max_speed_kmh, 1)} km/h before rollover (SRT ${srtText(out.srt)}, V = sqrt(127 SRT R), Eq. 9.1).`;
  await advisorySpeed(vehicleRef, caseRequest, radius);
  return out;
}

/** The advisory methods in words (docs/advisory.md, section 2): which kind each is. */
const METHODS = {
  "design-method": "Design Method (FHWA-SA-11-22 and TxDOT: the primary method)",
  "txdot-direct": "TxDOT Direct Method (from a measured car speed)",
  "ball-bank-16deg-2003": "Ball-bank 16 deg (MUTCD 2003; legacy)",
  "ball-bank-2009": "Ball-bank 16/14/12 deg by speed (MUTCD 2009; legacy)",
  "ball-bank-10-12-14deg": "Ball-bank 14/12/10 deg by speed (traditional; legacy)",
  "txdot-calculated-speed": "TxDOT calculated speed (legacy; never the sole basis)",
  "side-friction": "Side friction, Eq. 9.2 (this service's check)",
  rollover: "Rollover, Eq. 9.1 (this service's check)",
};

/** "50 mph (80.5 km/h)" with US plaques, "80 km/h" with metric ones. */
function plaque(out) {
  if (out.advisory_speed_kmh === null || out.advisory_speed_kmh === undefined) return "none (it cannot be computed)";
  return out.units === "us" ? `${fmt(out.advisory_speed_mph, 0)} mph (${fmt(out.advisory_speed_kmh, 1)} km/h)` : `${fmt(out.advisory_speed_kmh, 0)} km/h`;
}

/**
 * The advisory speed of the same curve beside its maximum speed (POST /v1/advisory-speed), when a posted speed is
 * typed: the plaque, which method sets it, each method's speed with its source -- a method the answer marks
 * unverified and gives no speed (the primary Design Method) is said so in words, never with a number -- the
 * treatment and the W1-13 warning.
 */
async function advisorySpeed(vehicleRef, caseRequest, radius) {
  const box = clear($("#advisory-result"));
  state.advisory = null;
  const posted = value($("#speed-posted"));
  if (posted === undefined || !(await api.has("post", "/v1/advisory-speed"))) return null;
  const out = await api.post(
    "/v1/advisory-speed",
    drop({
      vehicle: vehicleRef,
      ...srtOptions(caseRequest),
      ...designFields(),
      radius_m: radius,
      superelevation_percent: caseRequest.road?.bank_percent ?? 0,
      grade_percent: caseRequest.road?.slope_percent,
      posted_speed_kmh: posted,
      units: $("#speed-units").value || undefined,
    }),
  );
  state.advisory = out;
  const by = out.methods.find((m) => m.id === out.governed_by);
  const devices = out.treatment.devices.length ? out.treatment.devices.join("; ") : "none called for";
  const warning = out.truck_rollover_warning.recommended ? "recommended (this service's rule)" : "not recommended (this service's rule)";
  const rows = out.methods.map((m) => ({
    method: METHODS[m.id] || m.id,
    speed: m.speed_kmh,
    status: m.verified ? "verified" : "unverified",
    source: m.source,
  }));
  box.append(
    el(
      "p",
      { id: "advisory-line" },
      `Posted ${fmt(posted, 0)} km/h: advisory speed ${plaque(out)}, set by ${by ? METHODS[by.id] || by.id : out.governed_by}. `,
      `Treatment: ${devices}. Truck rollover warning (W1-13): ${warning}.`,
    ),
    scroller(
      "Advisory speed by method",
      table(
        [
          { key: "method", label: "Method", text: true },
          { key: "speed", label: "Speed [km/h]", format: (v) => (v === null || v === undefined ? "unverified: no speed" : fmt(v, 1)) },
          { key: "status", label: "Source read", text: true },
          { key: "source", label: "Source", text: true },
        ],
        rows,
        { caption: `The advisory speed of a curve of radius ${grouped(radius, 0)} m ${bankWords(caseRequest)}, each method's speed (before the plaque's rounding).` },
      ),
    ),
    el("ul", { class: "hint" }, out.notes.map((n) => el("li", {}, n))),
  );
  return out;
}

/**
 * A curve's design superelevation (POST /v1/superelevation) and, for the same design speed and e_max, the table of
 * superelevation by radius from R_min (POST /v1/superelevation/table, when the deployment has it).
 */
export async function superelevation() {
  const common = drop({ ...designFields(), design_speed_kmh: value($("#se-speed")), max_superelevation_percent: value($("#se-emax")) });
  const out = await api.post("/v1/superelevation", { ...common, radius_m: value($("#se-radius")) });
  // the line names every input it was computed from: the radius, the design speed and the maximum superelevation
  $("#super-result").textContent =
    `A curve of radius ${grouped(out.radius_m, 0)} m at ${fmt(out.design_speed_kmh, 0)} km/h (maximum superelevation ${num(out.max_superelevation_percent, 2)} %): ` +
    `superelevation ${fmt(out.superelevation_percent, 2)} %, leaving side friction ${fmt(out.side_friction, 3)} ` +
    `(the standard's maximum side friction at ${fmt(out.design_speed_kmh, 0)} km/h: ${fmt(out.f_max, 3)}); ` +
    `minimum radius at ${fmt(out.design_speed_kmh, 0)} km/h with ${num(out.max_superelevation_percent, 2)} %: ${grouped(out.min_radius_m, 0)} m. ${out.method}.`;
  const box = clear($("#super-table"));
  if (await api.has("post", "/v1/superelevation/table")) {
    const t = await api.post("/v1/superelevation/table", common);
    box.append(
      scroller(
        "Superelevation by radius",
        table(
          [
            { key: "radius_m", label: "R [m]", format: (v) => fmt(v, 0) },
            { key: "superelevation_percent", label: "e [%]", format: (v) => fmt(v, 2) },
            { key: "side_friction", label: "Side friction f", format: (v) => fmt(v, 3) },
          ],
          t.rows,
          { caption: `Superelevation by radius at ${fmt(t.design_speed_kmh, 0)} km/h, e_max ${fmt(t.max_superelevation_percent, 0)} % (${t.method}).` },
        ),
      ),
    );
  }
  return out;
}

/** A payload-table limit in words: `found` its value, `always-met` at least the range's end, `never-met` none. */
function limitText(limit, digits) {
  if (limit.status === "never-met" || limit.value === null) return "none meets it";
  return limit.status === "always-met" ? `\u2265 ${fmt(limit.value, digits)} (whole range)` : fmt(limit.value, digits);
}

function payloadRows(caption, rows, row, limit) {
  return scroller(
    caption,
    table(
      [
        { key: row.key, label: row.label, format: (v) => fmt(v, row.digits) },
        { key: "limit", label: limit.label, format: (v) => limitText(v, limit.digits) },
        { key: "limit", label: "SRT at the limit [g]", format: (v) => fmt(v.srt_g, 3) },
      ],
      rows,
      { caption, rowClass: (r) => (r.limit.status === "found" ? null : r.limit.status) },
    ),
  );
}

/**
 * For a built vehicle: the acceptable payload tables (POST /v1/vehicles/payload-table {spec, target_srt_g}) --
 * the largest payload mass at each load height and the largest load height at each payload mass (3D model, level
 * road: the table takes no case).
 */
export async function payloadTable(spec) {
  const request = { spec, target_srt_g: value($("#limit-target")) };
  const out = await api.post("/v1/vehicles/payload-table", request);
  const csv = async () => {
    const { data } = await api.call("POST", "/v1/vehicles/payload-table", { json: request, accept: "text/csv", as: "blob" });
    download("payload-table.csv", data);
  };
  $("#limits-result").append(
    el("h4", {}, "Acceptable payload of the built vehicle"),
    el("p", { id: "payload-info" }, `SRT of the spec as built ${srtText(out.srt_of_spec_g)} (3D model, level road); target ${srtText(out.target_srt_g)}.`),
    el(
      "div",
      { class: "two", id: "payload-tables" },
      payloadRows("Largest payload mass by load height", out.by_load_height, { key: "load_height_m", label: "Load height [m]", digits: 2 }, { label: "Largest payload [kg]", digits: 0 }),
      payloadRows("Largest load height by payload mass", out.by_payload_mass, { key: "payload_mass_kg", label: "Payload [kg]", digits: 0 }, { label: "Largest load height [m]", digits: 2 }),
    ),
    el("div", { class: "actions" }, el("button", { type: "button", id: "payload-csv", onclick: csv }, "Download the payload table (CSV)")),
  );
  return out;
}

/**
 * The acceptable load for a target SRT by overweight (POST /v1/srt/limits): a record's largest CG height above
 * the chassis (l12); a combination's largest vertical CG offset of its loads (d3), the field a combination has.
 */
export async function limits(vehicleRef, caseRequest, { combination = false } = {}) {
  const out = await api.post("/v1/srt/limits", {
    vehicle: vehicleRef,
    ...caseRequest,
    parameter: combination ? "vertical_offset_m" : "cg_height_above_chassis_m",
    target_srt_g: value($("#limit-target")),
  });
  const symbol = out.symbol || "l12";
  const box = clear($("#limits-result"));
  box.append(
    el("p", {}, `${out.description} for SRT >= ${srtText(out.target_srt_g)}${out.limit_on === "level_road" ? " on a level road (what the targets are judged on, whatever the bank)" : " on this road"}; this vehicle: ${symbol} = ${fmt(out.current_value, 3)} ${out.unit}.`),
    scroller(
      "Acceptable load by overweight",
      table(
        [
          { key: "overweight_percent", label: "Overweight [%]", format: (v) => fmt(v, 0) },
          { key: "value", label: `Largest ${symbol} [${out.unit}]`, format: (v) => fmt(v, 3) },
          { key: "status", label: "Status", text: true },
          { key: "srt_at_limit", label: "SRT at the limit [g]", format: (v) => fmt(v, 3) },
        ],
        out.table || [],
      ),
    ),
  );
  return out;
}
