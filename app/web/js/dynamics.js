// Section 6: the combination in motion (docs/dynamics.md). The PBS screening of a combination (POST /v1/pbs): each
// measure the linear yaw-roll model can judge with its value, unit, limit by level and whether that limit was read
// in the rules -- a limit the service could not read is "limit unverified", never a number -- the manoeuvres'
// conditions, the length's network level, what is not judged, and the plots of the lane change, the frequency
// response and the low-speed turn (SVG from /v1/dynamics/plots/*). The screening's caveat (a linear passive model:
// indicative only) comes first, on screen and on paper.

import * as api from "./api.js";
import { $, clear, el, fmt, num, scroller, svgNode, table } from "./dom.js";
import { value } from "./form.js";

export const state = { result: null, vehicleRef: null };

const drop = (obj) => Object.fromEntries(Object.entries(obj).filter(([, v]) => v !== undefined));

/** The PBS standards in words (docs/dynamics.md): name, and what the value is. */
const MEASURES = {
  srt: "Static rollover threshold (lowest roll-coupled unit)",
  rearward_amplification: "Rearward amplification (single lane change)",
  high_speed_transient_offtracking: "High-speed transient offtracking (single lane change)",
  yaw_damping: "Yaw damping ratio (pulse steer)",
  low_speed_swept_path: "Low-speed swept path width (90 deg turn)",
  tail_swing: "Tail swing (90 deg turn)",
  frontal_swing: "Frontal swing (90 deg turn)",
};

/** A label from an id the page does not know yet: `steer_tyre_demand` -> "Steer tyre demand". */
const words = (id) => {
  const text = String(id).replace(/[_-]+/g, " ");
  return text.charAt(0).toUpperCase() + text.slice(1);
};

const sentence = (text) => text.charAt(0).toUpperCase() + text.slice(1);

/** A request field in words: `lane_change_speed_kmh` -> "lane change speed" (its unit is said beside its value). */
const fieldWords = (id) => String(id).replace(/_(kmh|g|hz|mps2|m|s)$/, "").replace(/_/g, " ");

const UNIT_WORDS = { "-": "(ratio)", g: "g", m: "m" };

/** The combination choices: the page's own combination (when the vehicle chosen is one), then the presets. */
export function fillChoices(combinations) {
  const select = clear($("#dyn-vehicle"));
  select.append(el("option", { value: "" }, "this page's vehicle (a combination)"));
  for (const c of combinations) select.append(el("option", { value: c.id }, `${c.title} (${c.id})`));
}

/** What a limit says: its value and sense, or "limit unverified" when the rules' text could not be read. */
function limitText(limit, unit) {
  if (limit.limit === null || limit.limit === undefined || !limit.verified) return "limit unverified";
  const sense = limit.sense === "min" ? "at least" : "at most";
  return `${sense} ${num(limit.limit, 3)}${unit && unit !== "-" ? ` ${unit}` : ""}`;
}

/** The value of a measure, or why there is none (its note, e.g. a trailer that does not sway). */
function valueText(standard) {
  if (standard.value === null || standard.value === undefined) return standard.note ? `none: ${standard.note}` : "none";
  const digits = standard.unit === "m" ? 2 : 3;
  return fmt(standard.value, digits);
}

/** The table of measures: each with its value, unit, the limits per level, the level met and the source. */
export function pbsTable(result) {
  const rows = result.standards.map((s) => {
    const limits = s.limits || [];
    const allUnverified = limits.every((l) => !l.verified || l.limit === null);
    return {
      measure: MEASURES[s.id] || words(s.id),
      value: valueText(s),
      unit: UNIT_WORDS[s.unit] || s.unit,
      limits: allUnverified
        ? "limit unverified (levels 1-4: the rules' text could not be read)"
        : limits.map((l) => `level ${l.level}: ${limitText(l, s.unit)}`).join("; "),
      level: s.level === null || s.level === undefined ? "none judged (no verified limit)" : `level ${s.level}`,
      source: s.source,
    };
  });
  return table(
    [
      { key: "measure", label: "Measure", text: true },
      { key: "value", label: "Value", text: true },
      { key: "unit", label: "Unit", text: true },
      { key: "limits", label: "Limit by level", text: true },
      { key: "level", label: "Level met", text: true },
      { key: "source", label: "Source", text: true },
    ],
    rows,
    { caption: "PBS measures of the combination: value, unit, limit by level (read in the rules or unverified) and the level met by verified limits only." },
  );
}

/** The screening's caveat, first and in words: the answer's note and what the linear passive model leaves out. */
function caveat(result) {
  return el(
    "div",
    { class: "caveat", role: "note", id: "dyn-caveat" },
    el("strong", {}, `${sentence(result.note || "indicative screening, not a certification")}. `),
    "A linear passive yaw-roll model: no electronic stability control, no tyre saturation, no wheel lift-off; " +
      "above a unit's rollover threshold the model is no longer valid. It cannot certify a vehicle.",
  );
}

function conditionsList(result) {
  const c = result.conditions || {};
  const items = [
    `Single lane change at ${fmt(c.lane_change_speed_kmh, 0)} km/h, ${num(c.lane_change_frequency_hz, 2)} Hz, steer-axle lateral acceleration amplitude ${num(c.lane_change_amplitude_g, 3)} g`,
    `Pulse steer at ${fmt(c.pulse_steer_speed_kmh, 0)} km/h`,
    `Rearward amplification of the rearmost unit's ${c.ra_definition === "axle" ? "rearmost axle" : "centre of gravity"} over the steer axle`,
  ];
  if (c.unverified_defaults_used?.length) items.push(`Defaults used that are unverified: ${c.unverified_defaults_used.map(fieldWords).join(", ")}`);
  if (c.source) items.push(c.source);
  return el("ul", { class: "dyn-conditions" }, items.map((t) => el("li", {}, t)));
}

function lengthLine(result) {
  const n = result.network_level_by_length;
  if (!n) return null;
  return el(
    "p",
    {},
    `Length ${fmt(result.length_m, 2)} m: network level ${n.class_a ?? "none"} (class A) and ${n.class_b ?? "none"} (class B) by length ` +
      `(${n.source}${n.verified ? "" : "; unverified"}).`,
  );
}

function stabilityLine(result) {
  if (result.stable === false) return el("p", { class: "verdict fail" }, `Unstable at these speeds: the stability limit is ${fmt(result.stability_limit_kmh, 1)} km/h.`);
  const limit = typeof result.stability_limit_kmh === "number" ? `; it becomes unstable above ${fmt(result.stability_limit_kmh, 1)} km/h` : "";
  return el("p", {}, `Stable at the manoeuvres' speeds${limit}.`);
}

/** The three plots of the combination's dynamics, each from the service (SVG), with its caption. */
async function plots(vehicleRef, request) {
  const wanted = [
    ["/v1/dynamics/plots/lane-change", { vehicle: vehicleRef, speed_kmh: request.lane_change_speed_kmh, amplitude_g: request.lane_change_amplitude_g, ra_definition: request.ra_definition }, "Single lane change: lateral acceleration of every unit against time"],
    ["/v1/dynamics/plots/frequency-response", { vehicle: vehicleRef, speed_kmh: request.lane_change_speed_kmh, ra_definition: request.ra_definition }, "Rearward amplification against steer frequency (ISO 14791's approach)"],
    ["/v1/dynamics/plots/low-speed-turn", { vehicle: vehicleRef }, "Low-speed 90 deg turn: the paths of every unit's corners, to scale"],
  ];
  const figures = [];
  for (const [path, body, caption] of wanted) {
    if (!(await api.has("post", path))) continue;
    const svg = await api.postSvg(path, drop(body));
    figures.push(el("figure", { class: "plot keep" }, svgNode(svg), el("figcaption", {}, caption)));
  }
  return figures;
}

/** A parameter's name in words with its unit: `yaw_inertia_kgm2`, "kg m^2" -> "Yaw inertia [kg m^2]". */
function parameterLabel(name, unit) {
  const text = words(String(name).replace(/_(kgm2|m|per_rad)$/, ""));
  return unit && unit !== "-" ? `${text} [${unit}]` : text;
}

/** The answer's parameters that were given (not estimated): per unit and axle group, the value and where it was
 * typed (the vehicle's combination spec or the request's `dynamics`), as the answer's sources say. */
export function givenRows(result) {
  const p = result.parameters || {};
  const rows = [];
  const take = (unit, group, entry) => {
    for (const [name, v] of Object.entries(entry)) {
      if (!v || typeof v !== "object" || Array.isArray(v) || typeof v.source !== "string") continue;
      if (!v.source.startsWith("given")) continue;
      const where = /^given in ([^\s:]+)/.exec(v.source)?.[1] || "the request";
      const value = typeof v.value === "number" ? num(v.value, 6) : String(v.value);
      rows.push({ unit, group, field: parameterLabel(name, v.unit), value, where });
    }
  };
  for (const u of p.units || []) take(u.unit, "", u);
  for (const g of p.groups || []) take(g.unit, g.group, g);
  return rows;
}

/** What of the model's data was given, and where; or that every inertia, extent and cornering stiffness was estimated. */
function givenTable(result) {
  const rows = givenRows(result);
  if (!rows.length) {
    return el("p", { class: "dyn-given-none" }, "None given: every inertia, extent, width, axle spacing and cornering stiffness is estimated or a preset's sourced value (the answer's parameters say how).");
  }
  return scroller(
    "Data given for the dynamics",
    table(
      [
        { key: "unit", label: "Unit", text: true },
        { key: "group", label: "Axle group", text: true },
        { key: "field", label: "Value of", text: true },
        { key: "value", label: "Given", text: true },
        { key: "where", label: "Where given", text: true },
      ],
      rows,
      { caption: "The model's data given rather than estimated: per unit and axle group, the value and where it was typed." },
    ),
  );
}

/** Screen the combination: POST /v1/pbs and the plots. `pageVehicle`: the page's vehicle ({ref, combination}). */
export async function screen(pageVehicle) {
  const chosen = $("#dyn-vehicle").value;
  let vehicleRef;
  let name;
  if (chosen) {
    vehicleRef = chosen;
    name = $("#dyn-vehicle").selectedOptions[0].textContent;
  } else {
    const v = await pageVehicle();
    if (!v.combination && !v.ref?.combination_spec && !v.ref?.combination) {
      throw Object.assign(new Error("the dynamics need a combination (units, axle groups, couplings): choose a combination above, or one of the presets here"), { control: $("#dyn-vehicle") });
    }
    vehicleRef = v.ref;
    name = v.label;
  }
  const request = drop({
    vehicle: vehicleRef,
    lane_change_speed_kmh: value($("#dyn-lc-speed")),
    lane_change_amplitude_g: value($("#dyn-lc-amplitude")),
    pulse_steer_speed_kmh: value($("#dyn-pulse-speed")),
    ra_definition: $("#dyn-ra").value || undefined,
  });
  const result = await api.post("/v1/pbs", request);
  const figures = await plots(vehicleRef, request);
  Object.assign(state, { result, vehicleRef });
  const box = clear($("#dyn-results"));
  box.append(...nodes(result, name, figures));
  return { result, nodes: nodes(result, name, figures.map((f) => f.cloneNode(true))) };
}

/** The section's content (built twice: on screen and for the printout). */
function nodes(result, name, figures) {
  const validity = result.validity?.length ? el("ul", { class: "dyn-validity" }, result.validity.map((v) => el("li", {}, v))) : null;
  return [
    caveat(result),
    el("p", { class: "dyn-vehicle" }, `Combination: ${name}. Rules: ${result.rules_version}.`),
    stabilityLine(result),
    el("h4", { class: "with-next" }, "PBS measures"),
    el("div", { class: "keep" }, scroller("PBS measures", pbsTable(result))),
    validity ? el("h4", { class: "with-next" }, "Where the model's answer is limited") : null,
    validity,
    el("h4", { class: "with-next" }, "Data given for the model"),
    el("div", { class: "keep dyn-given" }, givenTable(result)),
    el("h4", { class: "with-next" }, "Manoeuvres"),
    conditionsList(result),
    lengthLine(result),
    el("h4", { class: "with-next" }, "Not judged by this screening"),
    el("p", { class: "dyn-not-judged" }, (result.not_judged || []).map(words).join(", ") + "."),
    // other schemes' limits: a number only where it was read (verified), else "limit unverified"
    ...(result.other_limits || []).map((o) =>
      el("p", { class: "hint" }, `${o.scheme}, ${MEASURES[o.standard] || words(o.standard)}: ${o.verified && o.limit !== null ? `${num(o.limit, 2)} ${o.unit}` : "limit unverified"} (${o.source}).`),
    ),
    figures.length ? el("h4", { class: "with-next" }, "Plots") : null,
    figures.length ? el("div", { class: "plots dyn-plots" }, figures) : null,
  ].filter(Boolean);
}
