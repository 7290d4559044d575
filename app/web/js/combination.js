// A combination on the page (GET /v1/combinations/{id}, POST /v1/srt with its whole-combination answer): a side
// view of its units (boxes, axle groups as wheels, couplings marked, the governing roll-coupled unit highlighted),
// the SRT of each roll-coupled unit and the lift-off sequence as tables.

import { $, clear, el, fmt, scroller, svgEl, table } from "./dom.js";

/** Words for the coupling kinds of the API. */
export const COUPLINGS = {
  "fifth-wheel": "fifth wheel",
  "b-coupling": "B-coupling (fifth wheel on the lead trailer)",
  pintle: "pintle / drawbar (no roll moment)",
  ball: "ball coupling (no roll moment)",
};

/** Words for the unit kinds of the API. */
export const KINDS = {
  tractor: "tractor",
  semitrailer: "semitrailer",
  "btrain-lead": "B-train lead trailer",
  dolly: "converter dolly",
  "rigid-truck": "rigid truck",
  "full-trailer": "full trailer",
};

const AXLE_SPACING_M = 1.3; // drawn only: the API gives each group's centre, not its axle spread

/** The units placed along the combination: each unit's origin [m behind the first unit's reference]. */
function layoutUnits(combination) {
  const origins = [0];
  combination.units.forEach((_, i) => {
    if (i === 0) return;
    origins.push(origins[i - 1] + (combination.couplings[i - 1]?.position_m ?? 0));
  });
  return combination.units.map((u, i) => {
    const xs = u.groups.flatMap((g) => [g.position_m - ((g.axles - 1) * AXLE_SPACING_M) / 2, g.position_m + ((g.axles - 1) * AXLE_SPACING_M) / 2]);
    const coupling = combination.couplings[i]?.position_m;
    if (coupling !== undefined) xs.push(coupling);
    const front = Math.min(0, ...xs) - (u.kind === "tractor" || u.kind === "rigid-truck" ? 1.3 : 0.9);
    const rear = Math.max(...xs, u.cg_position_m ?? 0) + 0.9;
    return { unit: u, origin: origins[i], front: origins[i] + front, rear: origins[i] + rear };
  });
}

/** The ids of the units of the governing roll-coupled unit (none without a whole-combination answer). */
export function governingUnits(result) {
  const units = result?.roll_coupled_units;
  if (!units?.length) return [];
  const i = Number.isInteger(result.governing_unit) ? result.governing_unit : units.findIndex((u) => u.srt === result.srt);
  return units[Math.max(0, i)]?.units || [];
}

/** A side view (SVG) of the combination: front to the left; the governing roll-coupled unit's units highlighted. */
export function sideView(combination, result) {
  const placed = layoutUnits(combination);
  const governing = new Set(governingUnits(result));
  const x0 = Math.min(...placed.map((p) => p.front)) - 0.5;
  const x1 = Math.max(...placed.map((p) => p.rear)) + 0.5;
  const k = 40; // px per m
  const width = (x1 - x0) * k;
  const height = 150;
  const X = (m) => ((m - x0) * k).toFixed(1);
  const svg = svgEl("svg", { viewBox: `0 0 ${width.toFixed(0)} ${height}`, role: "img", class: "combination-view", id: "combination-svg" });
  const names = combination.units.map((u) => u.id).join(", ");
  svg.setAttribute("aria-label", `Side view of the combination (front to the left): ${names}${governing.size ? `; governing: ${[...governing].join(" + ")}` : ""}`);
  svg.append(svgEl("line", { x1: 0, y1: 128, x2: width.toFixed(0), y2: 128, class: "ground" }));
  placed.forEach((p, i) => {
    const towing = p.unit.kind === "tractor" || p.unit.kind === "rigid-truck" || p.unit.kind === "dolly";
    const top = p.unit.kind === "dolly" ? 88 : towing ? 52 : 34;
    const bottom = p.unit.kind === "dolly" ? 104 : towing ? 104 : 92;
    const g = svgEl("g", { class: governing.has(p.unit.id) ? "unit governing" : "unit", "data-unit": p.unit.id });
    const title = svgEl("title");
    title.textContent = `${p.unit.id}: ${p.unit.title || KINDS[p.unit.kind] || p.unit.kind}${governing.has(p.unit.id) ? " (governing roll-coupled unit)" : ""}`;
    g.append(title);
    g.append(svgEl("rect", { x: X(p.front), y: top, width: ((p.rear - p.front) * k).toFixed(1), height: bottom - top, rx: 3, class: "body" }));
    if (p.unit.kind === "tractor" || p.unit.kind === "rigid-truck") {
      g.append(svgEl("rect", { x: X(p.front), y: 18, width: (2.1 * k).toFixed(1), height: 34, rx: 4, class: "cab" }));
    }
    for (const group of p.unit.groups) {
      for (let a = 0; a < group.axles; a += 1) {
        const at = p.origin + group.position_m + (a - (group.axles - 1) / 2) * AXLE_SPACING_M;
        g.append(svgEl("circle", { cx: X(at), cy: 114, r: 13, class: "wheel", "data-group": group.id }));
      }
    }
    const label = svgEl("text", { x: X((p.front + p.rear) / 2), y: top - 4, "text-anchor": "middle", class: "label" });
    label.textContent = p.unit.id;
    g.append(label);
    svg.append(g);
    const c = combination.couplings[i];
    if (c) {
      const at = p.origin + c.position_m;
      const mark = svgEl("path", { d: `M ${X(at)} ${top - 2} l -7 -11 l 14 0 z`, class: `coupling ${c.roll_stiffness_knm_per_rad === null ? "free" : "rigid"}`, "data-kind": c.kind });
      const t = svgEl("title");
      t.textContent = `${COUPLINGS[c.kind] || c.kind} between ${p.unit.id} and ${combination.units[i + 1]?.id}`;
      mark.append(t);
      svg.append(mark);
    }
  });
  return svg;
}

const joinUnits = (units) => units.join(" + ");

/** The SRT of each roll-coupled unit, the governing one marked. */
export function unitsTable(result) {
  const governing = joinUnits(governingUnits(result));
  const rows = result.roll_coupled_units.map((u, i) => ({ ...u, n: i + 1, name: joinUnits(u.units), governs: joinUnits(u.units) === governing }));
  return table(
    [
      { key: "n", label: "#" },
      { key: "name", label: "Roll-coupled unit", text: true },
      { key: "srt", label: "SRT [g]", format: (v) => fmt(v, 3) },
      { key: "governs", label: "Governs", text: true, format: (v) => (v ? "\u2714 governs (lowest SRT)" : "") },
      { key: "ended_by", label: "What ended it", text: true },
    ],
    rows,
    { rowClass: (r) => (r.governs ? "governing" : null) },
  );
}

/** The lift-off sequence: which axle group lifts off at which lateral acceleration. */
export function liftTable(result) {
  const rows = (result.lift_sequence || []).map((s, i) => ({ ...s, n: i + 1 }));
  return table(
    [
      { key: "n", label: "#" },
      { key: "unit", label: "Unit", text: true },
      { key: "group", label: "Axle group", text: true },
      { key: "ay_g", label: "Lifts off at ay [g]", format: (v) => fmt(v, 3) },
    ],
    rows,
  );
}

/** "Governed by roll-coupled unit 2 (dolly + trailer2), SRT 0.389 g." */
export function governingText(result) {
  const units = result.roll_coupled_units;
  const i = Number.isInteger(result.governing_unit) ? result.governing_unit : 0;
  const u = units[i];
  if (!u) return "";
  const of = units.length > 1 ? `roll-coupled unit ${i + 1} of ${units.length} ` : "the one roll-coupled unit ";
  return `Governed by ${of}(${joinUnits(u.units)}), SRT ${fmt(u.srt, 3)} g.`;
}

/** The combination's part of the result panel: side view, governing unit, the two tables; hidden otherwise. */
export function show(combination, result) {
  const box = clear($("#combination-result"));
  const whole = Array.isArray(result?.roll_coupled_units) && result.roll_coupled_units.length > 0;
  box.hidden = !combination && !whole;
  if (box.hidden) return;
  if (combination) box.append(el("figure", { class: "combination-figure" }, sideView(combination, whole ? result : null), el("figcaption", { class: "hint" }, "Side view, front to the left: units, axle groups (wheels) and couplings (triangles; hollow: no roll moment); the governing roll-coupled unit is highlighted.")));
  if (!whole) {
    box.append(el("p", { class: "hint" }, `The ${result?.model || ""} model answers for the last unit; choose the whole-combination model for each roll-coupled unit's SRT.`));
    return;
  }
  box.append(
    el("p", { id: "governing-unit", class: "governing-line" }, governingText(result)),
    el("h4", {}, "SRT of each roll-coupled unit"),
    scroller("SRT of each roll-coupled unit", el("div", { id: "units-table" }, unitsTable(result))),
    el("h4", {}, "Lift-off sequence"),
    scroller("Lift-off sequence", el("div", { id: "lift-table" }, liftTable(result))),
  );
  if (typeof result.last_unit_front_llt_ratio === "number") {
    box.append(el("p", { class: "hint" }, `Last unit: LLTf/LLTr at its limit ${fmt(result.last_unit_front_llt_ratio, 3)} (what the thesis's 3D model of the last unit takes as front_llt_ratio).`));
  }
}
