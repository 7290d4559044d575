// "Build the combination": each unit of a combination from what can be measured of it (axle groups with their
// tyres and suspension from the roll component library, tare mass and CG or its rear-group load, payloads, deck), the
// couplings between them, units added and removed. Each payload gives its height one of the spec's ways, chosen per
// payload: a load on a level or a sloping deck, a CG height, or a liquid in a tank (PayloadSpec, TankSpec). The page
// posts the combination spec to POST /v1/combinations/build (and the computations take it as
// `"vehicle": {"combination_spec": {...}}`); a 422 names the spec field as typed
// (`combination_spec.units.1.tare.mass_kg`), shown beside its box. The library's suspension and fifth-wheel ids are
// the ones the service's OpenAPI document lists for the spec (RollSuspensionSpec.type, CouplingSpec.fifth_wheel).

import * as api from "./api.js";
import { COUPLINGS, KINDS } from "./combination.js";
import { $, $$, clear, el, fieldLabel, fmt, grouped, num, scroller, table } from "./dom.js";
import { value } from "./form.js";
import * as stale from "./stale.js";

/** Per unit kind: its axle groups (names for people) and its reference point (engine UNIT_KINDS). */
export const KIND_INFO = {
  tractor: { groups: ["Steer axle group", "Drive axle group"], ref: "the steer group centre", towing: true },
  "rigid-truck": { groups: ["Steer axle group", "Rear axle group"], ref: "the steer group centre", towing: true },
  semitrailer: { groups: ["Axle group"], ref: "the kingpin" },
  "btrain-lead": { groups: ["Axle group"], ref: "the kingpin" },
  dolly: { groups: ["Axle group"], ref: "the drawbar eye" },
  "full-trailer": { groups: ["Front axle group (turntable)", "Rear axle group"], ref: "the drawbar eye" },
};

/** Axles and tyres per axle a new group of a unit kind starts with (its other boxes start empty). */
const NEW_GROUPS = {
  tractor: [{ axles: 1, tyres_per_axle: 2 }, { axles: 2, tyres_per_axle: 4 }],
  "rigid-truck": [{ axles: 1, tyres_per_axle: 2 }, { axles: 2, tyres_per_axle: 4 }],
  semitrailer: [{ axles: 3, tyres_per_axle: 4 }],
  "btrain-lead": [{ axles: 3, tyres_per_axle: 4 }],
  dolly: [{ axles: 2, tyres_per_axle: 4 }],
  "full-trailer": [{ axles: 1, tyres_per_axle: 4 }, { axles: 2, tyres_per_axle: 4 }],
};

/**
 * The default: the preset `tractor-semitrailer-table15` in measurable terms, as tests/engine/test_combination_builder.py
 * (`table15_spec`) and docs/vehicles.md (Sec. 8, "Rebuilding a preset") restate it from its sources: TruckSim's
 * '2A Day Cab' weighed with its axles (4455 + 362 + 679 = 5496 kg; CG 1.0515 m high, 1.3322 m behind the steer
 * axle), tyre size 11R22.5, suspensions trucksim-steer-leaf-5.5t / trucksim-drive-leaf-8.5t, fifth wheel
 * trucksim-fifth-wheel 2.6 m behind the steer axle, 1.07 m high; the trailer as the thesis's Table 15 states it
 * (W / g = 364.147 kN / 9.81 = 37 120 kg at 2.0 m, a = 5.0 m, L = 8.7 m, T = 1.815 m, kT = 980 kN/m, lr = 0.51 m,
 * kLs b^2/2 = 2500 x 0.95^2 / 2 kN m/rad, roll centre lr + ls = 0.715 m, b = 0.95 m). CG heights rounded to 0.1 mm.
 */
export const TABLE15_SPEC = {
  title: "Tractor and semitrailer (Table 15, from measurable data)",
  units: [
    {
      id: "tractor",
      kind: "tractor",
      axle_groups: [
        { axles: 1, tyres_per_axle: 2, track_m: 2.03, position_m: 0, tyre: { size: "11R22.5" }, suspension: { type: "trucksim-steer-leaf-5.5t" } },
        { axles: 1, tyres_per_axle: 4, track_m: 1.815, position_m: 3.5, tyre: { size: "11R22.5" }, suspension: { type: "trucksim-drive-leaf-8.5t" } },
      ],
      tare: { mass_kg: 5496, cg_height_m: 1.0515, cg_from_kingpin_m: 1.3322 },
    },
    {
      id: "trailer",
      kind: "semitrailer",
      axle_groups: [
        {
          axles: 3,
          tyres_per_axle: 4,
          track_m: 1.815,
          position_m: 8.7,
          tyre: { stiffness_kn_per_m: 980, loaded_radius_m: 0.51 },
          suspension: {
            type: "trucksim-trailer-leaf-18t",
            roll_stiffness_knm_per_rad: 1128.125,
            roll_centre_height_m: 0.715,
            spring_spacing_m: 0.95,
            lash_deg: 0,
            unsprung_cg_height_m: 0.51,
          },
        },
      ],
      tare: { mass_kg: 37120, cg_height_m: 2.0, cg_from_kingpin_m: 5.0 },
    },
  ],
  couplings: [{ kind: "fifth-wheel", position_m: 2.6, height_m: 1.07, fifth_wheel: "trucksim-fifth-wheel" }],
};

const round6 = (v) => (typeof v === "number" ? Number(v.toPrecision(6)) : v);

/**
 * A combination preset's record (GET /v1/combinations/{id}) restated as a spec: each group's per-axle values as
 * explicit tyre and suspension data, each unit's tare = its sprung mass plus its axles, with the CG of the two
 * (the inverse of the builder's m_s = sum(m) - n m_u, z_s = (sum(m z) - n m_u z_u) / m_s); rounded to 6 figures.
 */
export function specFromRecord(c, title) {
  const units = c.units.map((u) => {
    const axles = u.groups.map((g) => ({ m: g.axles * g.unsprung_mass_kg, z: g.unsprung_cg_height_m, x: g.position_m }));
    const mass = u.sprung_mass_kg + axles.reduce((s, a) => s + a.m, 0);
    const z = (u.sprung_mass_kg * u.cg_height_m + axles.reduce((s, a) => s + a.m * a.z, 0)) / mass;
    const x = (u.sprung_mass_kg * u.cg_position_m + axles.reduce((s, a) => s + a.m * a.x, 0)) / mass;
    const suspension = (g) => {
      const s = { roll_stiffness_knm_per_rad: g.roll_stiffness_knm_per_rad, roll_centre_height_m: g.roll_centre_height_m, lash_deg: g.lash_deg ?? 0, unsprung_mass_kg: g.unsprung_mass_kg, unsprung_cg_height_m: g.unsprung_cg_height_m };
      if (g.spring_spacing_m != null) s.spring_spacing_m = g.spring_spacing_m;
      return Object.fromEntries(Object.entries(s).map(([k, v]) => [k, round6(v)]));
    };
    return {
      id: u.id,
      kind: u.kind,
      ...(u.title ? { title: u.title } : {}),
      axle_groups: u.groups.map((g) => ({ id: g.id, axles: g.axles, tyres_per_axle: g.tyres_per_axle, track_m: round6(g.track_m), position_m: round6(g.position_m), tyre: { stiffness_kn_per_m: round6(g.tyre_stiffness_kn_per_m) }, suspension: suspension(g) })),
      tare: { mass_kg: round6(mass), cg_height_m: round6(z), cg_from_kingpin_m: round6(x) },
    };
  });
  const couplings = c.couplings.map((k) => {
    const out = { kind: k.kind, position_m: round6(k.position_m), height_m: round6(k.height_m) };
    if (k.roll_stiffness_knm_per_rad != null) Object.assign(out, { roll_stiffness_knm_per_rad: round6(k.roll_stiffness_knm_per_rad), lash_deg: round6(k.lash_deg ?? 0) });
    return out;
  });
  const spec = { title, units, couplings };
  if (typeof c.front_llt_ratio === "number") spec.front_llt_ratio = c.front_llt_ratio;
  return spec;
}

export const state = {
  library: { suspensions: [], fifthWheels: [], dynUnit: [], dynGroup: [] }, // the ids and fields the spec schema lists
  combinations: [], // GET /v1/combinations
  pending: null, // a spec from the link, shown once the library is read
  built: null, // the last POST /v1/combinations/build answer
  extra: [], // per unit: the spec parts the editor has no box for, kept as they are
};

// ------------------------------------------------------------------------------------------ the boxes

const idOf = (path) => `cb-${path.replace(/\./g, "-")}`;
const fieldsFor = (path) => `combination_spec.${path} vehicle.combination_spec.${path}`;
const get = (obj, path) => path.split(".").reduce((node, k) => (node == null ? undefined : node[k]), obj);

/** One labelled box for the spec path `path` (relative to the spec), its value from `spec`. */
function box(spec, path, label, { kind = "number", options, hint, extraFields = "", wide = false } = {}) {
  const id = idOf(path);
  const v = get(spec, path);
  const fields = `${fieldsFor(path)}${extraFields ? ` ${extraFields}` : ""}`;
  let control;
  if (kind === "select") {
    control = el("select", { id, "data-cb": path, "data-field": fields, "data-int": options.int ? "" : null });
    for (const [val, text] of options.items) control.append(el("option", { value: val }, text));
    if (v !== undefined && v !== null && !options.items.some(([val]) => val === String(v))) control.append(el("option", { value: String(v) }, String(v)));
    control.value = v === undefined || v === null ? options.items[0][0] : String(v);
  } else {
    control = el("input", { id, "data-cb": path, "data-field": fields, inputmode: kind === "text" ? null : kind === "int" ? "numeric" : "decimal", type: "text", spellcheck: kind === "text" ? "false" : null, list: options?.list || null, value: v === undefined || v === null ? "" : String(v) });
  }
  if (hint) control.setAttribute("aria-describedby", `${id}-hint`);
  return el("div", { class: wide ? "field wide" : "field" }, el("label", { for: id }, label), control, hint ? el("span", { class: "hint", id: `${id}-hint` }, hint) : null);
}

/**
 * The yaw-roll model's optional fields of a unit or a group as the OpenAPI document describes them (generated from
 * their one definition, engine.dynamics UNIT_DATA_DOCS / GROUP_DATA_DOCS): per field its label (the description's
 * first clause and its unit), the rest of the description with the accepted range as the hint, and the choices of a
 * choice.
 */
export function dynamicsFields(schema) {
  return Object.entries(schema?.properties || {}).map(([name, prop]) => {
    const description = String(prop.description || name);
    const unit = /Unit: (.+?)\. Thesis symbol/.exec(description)?.[1] || "-";
    const text = description.replace(/ Unit: .*$/, "").replace(/ \((estimated|the default) when left out\)\.$/, "");
    const cut = text.search(/[,;]/);
    const head = cut > 0 ? text.slice(0, cut) : text;
    const rest = cut > 0 ? text.slice(cut + 1).trim() : "";
    const range = (prop.anyOf || []).find((a) => a.type === "number");
    const choices = (prop.anyOf || []).find((a) => a.enum)?.enum || null;
    const bounds = range ? `from ${range.minimum} to ${range.maximum}${unit !== "-" ? ` ${unit}` : ""}` : "";
    const left = choices ? "blank: the default" : "blank: estimated";
    const hint = [rest && rest.charAt(0).toUpperCase() + rest.slice(1), bounds, left].filter(Boolean).join("; ");
    return { name, label: unit !== "-" ? `${head} [${unit}]` : head, hint: `${hint}.`, choices };
  });
}

/** A unit's or a group's folded boxes for the yaw-roll model (open when one is given), at spec path `p`.dynamics. */
function dynamicsBoxes(spec, p, fields) {
  if (!fields.length) return null;
  const anyGiven = fields.some((f) => given(get(spec, `${p}.dynamics.${f.name}`)));
  return el(
    "details",
    { class: "cb-dynamics", open: anyGiven || null },
    el("summary", {}, "For the dynamics (optional)"),
    el("p", { class: "hint" }, "Used by the dynamics and the PBS screening only (the rollover threshold does not use them); each box left blank is estimated, and the answer says how."),
    el(
      "div",
      { class: "grid" },
      fields.map((f) =>
        box(spec, `${p}.dynamics.${f.name}`, f.label, {
          hint: f.hint,
          kind: f.choices ? "select" : "number",
          options: f.choices ? { items: [["", "(default)"], ...f.choices.map((c) => [c, c])] } : undefined,
          extraFields: fieldsFor(`${p}.dynamics`),
        }),
      ),
    ),
  );
}

const suspensionItems = () => [["", "(none: explicit values)"], ...state.library.suspensions.map((s) => [s, s])];
const fifthWheelItems = () => [["", "(none: explicit values)"], ...state.library.fifthWheels.map((s) => [s, s])];

function groupBox(spec, i, j, kind) {
  const p = `units.${i}.axle_groups.${j}`;
  const ref = KIND_INFO[kind]?.ref || "the reference point";
  const name = KIND_INFO[kind]?.groups[j] || `Axle group ${j + 1}`;
  const explicit = ["tyre.stiffness_kn_per_m", "tyre.loaded_radius_m", "suspension.roll_stiffness_knm_per_rad", "suspension.roll_centre_height_m", "suspension.spring_spacing_m", "suspension.lash_deg", "suspension.unsprung_mass_kg", "suspension.unsprung_cg_height_m"];
  const anyExplicit = explicit.some((k) => get(spec, `${p}.${k}`) !== undefined && get(spec, `${p}.${k}`) !== null);
  return el(
    "fieldset",
    { class: "cb-group", "data-group": String(j) },
    el("legend", {}, name),
    el(
      "div",
      { class: "grid" },
      box(spec, `${p}.id`, "Group name (optional)", { kind: "text", hint: "Blank: steer and drive, front and rear, or the unit's name. The lift-off sequence names it." }),
      box(spec, `${p}.axles`, "Axles [count]", { kind: "int", extraFields: fieldsFor(p) }),
      box(spec, `${p}.tyres_per_axle`, "Tyres per axle", { kind: "select", options: { int: true, items: [["2", "2 (single tyres)"], ["4", "4 (duals)"]] } }),
      box(spec, `${p}.track_m`, "Track [m]"),
      box(spec, `${p}.position_m`, `Group centre behind ${ref} [m]`),
      box(spec, `${p}.axle_spacing_m`, "Axle spacing [m]", { hint: "Optional; the dynamics place the axles at it (blank: estimated there)." }),
      box(spec, `${p}.tyre.size`, "Tyre size", { kind: "text", options: { list: "cb-tyre-sizes" }, extraFields: fieldsFor(`${p}.tyre`) }),
      box(spec, `${p}.suspension.type`, "Suspension (roll library)", { kind: "select", options: { items: suspensionItems() }, extraFields: fieldsFor(`${p}.suspension`) }),
    ),
    el(
      "details",
      { class: "cb-explicit", open: anyExplicit || null },
      el("summary", {}, "Explicit tyre and suspension values (over the library's)"),
      el(
        "div",
        { class: "grid" },
        box(spec, `${p}.tyre.stiffness_kn_per_m`, "Tyre vertical rate [kN/m]"),
        box(spec, `${p}.tyre.loaded_radius_m`, "Tyre loaded radius [m]"),
        box(spec, `${p}.suspension.roll_stiffness_knm_per_rad`, "Roll stiffness per axle [kN m/rad]"),
        box(spec, `${p}.suspension.roll_centre_height_m`, "Roll-centre height [m]"),
        box(spec, `${p}.suspension.spring_spacing_m`, "Spring spacing [m]"),
        box(spec, `${p}.suspension.lash_deg`, "Suspension lash [deg]"),
        box(spec, `${p}.suspension.unsprung_mass_kg`, "Unsprung mass per axle [kg]"),
        box(spec, `${p}.suspension.unsprung_cg_height_m`, "Unsprung CG height [m]"),
      ),
    ),
    dynamicsBoxes(spec, p, state.library.dynGroup),
  );
}

/**
 * How a payload's height is given (the engine's payload_item: exactly one of a deck load, a CG height or a tank),
 * a deck load on a level or a sloping deck; per way, the spec fields it has boxes for.
 */
export const PAYLOAD_KINDS = {
  deck: { text: "Level deck: deck and load heights", fields: ["deck_height_m", "load_height_m", "distribution"] },
  sloped: { text: "Sloping deck: heights at front and rear", fields: ["deck_height_m", "deck_height_rear_m", "load_height_m", "load_height_rear_m", "distribution"] },
  cg: { text: "CG height, as measured", fields: ["cg_height_m"] },
  tank: { text: "Liquid in a tank: size and fill", fields: ["tank"] },
};
/** The payload fields that say how high it sits (one way's fields; the others are dropped when the way changes). */
const HEIGHT_FIELDS = ["deck_height_m", "load_height_m", "deck_height_rear_m", "load_height_rear_m", "distribution", "cg_height_m", "tank"];
/** The way a payload's height is given, as chosen in the editor (kept on the spec object through a redraw). */
const WAY = Symbol("payload kind");
const given = (v) => v !== undefined && v !== null && v !== "";

/** The way a payload of a spec gives its height (a tank, a sloping deck, a level deck, a CG height). */
export function payloadKind(payload) {
  if (payload?.[WAY]) return payload[WAY];
  if (given(payload?.tank)) return "tank";
  if (given(payload?.deck_height_rear_m) || given(payload?.load_height_rear_m)) return "sloped";
  if (!given(payload?.deck_height_m) && given(payload?.cg_height_m)) return "cg";
  return "deck";
}

const DISTRIBUTIONS = [["uniform", "Uniform density (CG at mid-height)"], ["mixed-freight", "Mixed freight (CG at 0.4 of the height)"]];

function payloadBox(spec, i, k, ref) {
  const p = `units.${i}.payloads.${k}`;
  const way = payloadKind(get(spec, p));
  const wayId = `${idOf(p)}-kind`;
  const boxes = {
    deck: () => [
      box(spec, `${p}.deck_height_m`, "Deck height above the road [m]"),
      box(spec, `${p}.load_height_m`, "Top of the load above the road [m]"),
      box(spec, `${p}.distribution`, "Load distribution", { kind: "select", options: { items: DISTRIBUTIONS } }),
    ],
    sloped: () => [
      box(spec, `${p}.deck_height_m`, "Deck height at the load's front [m]"),
      box(spec, `${p}.deck_height_rear_m`, "Deck height at the load's rear [m]", { hint: "Blank: the front's (a level deck)." }),
      box(spec, `${p}.load_height_m`, "Top of the load at its front [m]", { hint: "Above the deck there." }),
      box(spec, `${p}.load_height_rear_m`, "Top of the load at its rear [m]", { hint: "At least the deck there; blank: parallel to the deck." }),
      box(spec, `${p}.distribution`, "Load distribution", { kind: "select", options: { items: DISTRIBUTIONS } }),
    ],
    cg: () => [box(spec, `${p}.cg_height_m`, "Payload CG height above the road [m]", { extraFields: fieldsFor(`${p}.deck_height_m`) })],
    tank: () => [
      box(spec, `${p}.tank.shape`, "Tank cross-section", { kind: "select", options: { items: [["circular", "Circular"], ["elliptical", "Elliptical"]] }, extraFields: fieldsFor(`${p}.tank`) }),
      box(spec, `${p}.tank.height_m`, "Tank inside height [m]", { hint: "A circular tank's inside diameter; above 0." }),
      box(spec, `${p}.tank.bottom_height_m`, "Tank inside bottom above the road [m]", { hint: "Above 0." }),
      box(spec, `${p}.tank.fill_height_m`, "Liquid depth [m]", { hint: "Above 0, at most the tank's height; or give the fraction." }),
      box(spec, `${p}.tank.fill_fraction`, "Or: fill by volume, fraction full [-]", { hint: "Above 0, at most 1 (0.8 = 80 % full)." }),
    ],
  };
  const select = el("select", { id: wayId, "data-payload-kind": "", "data-unit": String(i), "data-payload": String(k) });
  for (const [val, { text }] of Object.entries(PAYLOAD_KINDS)) select.append(el("option", { value: val }, text));
  select.value = way;
  return el(
    "fieldset",
    { class: "cb-payload", "data-payload": String(k), "data-kind": way },
    el("legend", {}, `Payload ${k + 1}`),
    el(
      "div",
      { class: "grid" },
      box(spec, `${p}.mass_kg`, "Payload mass [kg]", { extraFields: fieldsFor(p) }),
      el("div", { class: "field wide" }, el("label", { for: wayId }, "Its height given as"), select),
      boxes[way](),
    ),
    el(
      "div",
      { class: "grid" },
      box(spec, `${p}.front_from_kingpin_m`, `Load front behind ${ref} [m]`, { hint: "Blank: the load centred on the deck." }),
      box(spec, `${p}.length_m`, "Load length [m]", { hint: "Blank: the deck's length." }),
      way === "sloped" ? null : box(spec, `${p}.cg_from_kingpin_m`, `Or: payload CG behind ${ref} [m]`),
    ),
    el("div", { class: "actions" }, el("button", { type: "button", class: "cb-remove-payload", "data-unit": String(i), "data-payload": String(k) }, `Remove payload ${k + 1}`)),
  );
}

function couplingBox(spec, k, towing) {
  const p = `couplings.${k}`;
  const ref = KIND_INFO[towing]?.ref || "the reference point";
  return el(
    "fieldset",
    { class: "cb-coupling", "data-coupling": String(k) },
    el("legend", {}, `Coupling ${k + 1}: unit ${k + 1} to unit ${k + 2}`),
    el(
      "div",
      { class: "grid" },
      box(spec, `${p}.kind`, "Coupling", { kind: "select", options: { items: Object.entries(COUPLINGS) }, extraFields: fieldsFor(p) }),
      box(spec, `${p}.position_m`, `Position behind ${ref} of unit ${k + 1} [m]`),
      box(spec, `${p}.height_m`, "Height above the road [m]"),
      box(spec, `${p}.fifth_wheel`, "Fifth wheel (roll library)", { kind: "select", options: { items: fifthWheelItems() } }),
      box(spec, `${p}.roll_stiffness_knm_per_rad`, "Or: roll stiffness [kN m/rad]"),
      box(spec, `${p}.lash_deg`, "Lash each way [deg]"),
    ),
  );
}

function unitBox(spec, i) {
  const u = spec.units[i];
  const kind = u.kind;
  const ref = KIND_INFO[kind]?.ref || "the reference point";
  const rearGroup = KIND_INFO[kind]?.groups.at(-1) || "rear axle group";
  const p = `units.${i}`;
  const groups = (u.axle_groups || []).map((_, j) => groupBox(spec, i, j, kind));
  const payloads = (u.payloads || []).map((_, k) => payloadBox(spec, i, k, ref));
  return el(
    "fieldset",
    { class: "cb-unit", "data-unit": String(i) },
    el("legend", {}, `Unit ${i + 1}: ${KINDS[kind] || kind}`),
    el(
      "div",
      { class: "grid" },
      box(spec, `${p}.kind`, "Kind of unit", { kind: "select", options: { items: Object.entries(KINDS).filter(([k]) => k in KIND_INFO) }, extraFields: fieldsFor(p) }),
      box(spec, `${p}.id`, "Name (unique)", { kind: "text" }),
      box(spec, `${p}.title`, "Description (optional)", { kind: "text", hint: "A name for people, kept with the built unit." }),
    ),
    el("p", { class: "hint" }, `Positions along the unit are metres behind ${ref}.`),
    groups,
    el(
      "fieldset",
      { class: "cb-tare" },
      el("legend", {}, "Tare (weighed with its axles)"),
      el(
        "div",
        { class: "grid" },
        box(spec, `${p}.tare.mass_kg`, "Tare mass [kg]", { extraFields: fieldsFor(`${p}.tare`) }),
        box(spec, `${p}.tare.cg_height_m`, "Tare CG height above the road [m]"),
        box(spec, `${p}.tare.cg_from_kingpin_m`, `Tare CG behind ${ref} [m]`),
        box(spec, `${p}.tare.rear_group_load_kg`, `Or: tare load on the ${rearGroup.toLowerCase()} [kg]`, {
          hint: `Optional; blank: not given. Its weighbridge load, unladen, instead of the tare CG position: x = L m_rear / m (L: front support to this group).`,
        }),
      ),
    ),
    el(
      "fieldset",
      { class: "cb-deck" },
      el("legend", {}, "Deck (load space, for the payloads' positions)"),
      el("div", { class: "grid" }, box(spec, `${p}.deck.front_from_kingpin_m`, `Deck front behind ${ref} [m]`, { extraFields: fieldsFor(`${p}.deck`) }), box(spec, `${p}.deck.length_m`, "Deck length [m]")),
    ),
    payloads,
    dynamicsBoxes(spec, p, state.library.dynUnit),
    el(
      "div",
      { class: "actions" },
      el("button", { type: "button", class: "cb-add-payload", "data-unit": String(i) }, `Add a payload to unit ${i + 1}`),
      spec.units.length > 1 ? el("button", { type: "button", class: "cb-remove-unit", "data-unit": String(i) }, `Remove unit ${i + 1}`) : null,
    ),
  );
}

/** Draw the editor for `spec` (the boxes are the spec from now on). */
export function render(spec) {
  suggestSizes(spec.units.flatMap((u) => (u.axle_groups || []).map((g) => g?.tyre?.size)));
  const root = clear($("#cb-units"));
  $("#cb-title").value = spec.title || "";
  $("#cb-front-llt").value = spec.front_llt_ratio ?? "";
  spec.units.forEach((_, i) => {
    root.append(unitBox(spec, i));
    if (i < spec.units.length - 1) root.append(couplingBox(spec, i, spec.units[i].kind));
  });
  // what has no box is kept as it is (and said so under its unit)
  const boxed = new Set($$("[data-cb]", root).map((c) => c.dataset.cb));
  state.extra = spec.units.map((u, i) => strip(u, `units.${i}`, boxed) || {});
  state.extra.forEach((extra, i) => {
    const kept = [...leafPaths(extra)];
    if (kept.length) $(`#cb-units .cb-unit[data-unit="${i}"] > .hint`).append(` Kept from the spec as it is (no box here): ${kept.join(", ")}.`);
  });
}

const isObject = (v) => v !== null && typeof v === "object" && !Array.isArray(v);

/** `node` without the paths that have a box (undefined when nothing is left); arrays keep their positions. */
function strip(node, prefix, boxed) {
  if (Array.isArray(node)) {
    const out = node.map((v, k) => strip(v, `${prefix}.${k}`, boxed) ?? {});
    return out.some((v) => Object.keys(v).length) ? out : undefined;
  }
  if (!isObject(node)) return undefined;
  const out = {};
  for (const [k, v] of Object.entries(node)) {
    const p = `${prefix}.${k}`;
    if (boxed.has(p) || v === undefined || v === null) continue;
    if (Array.isArray(v) || isObject(v)) {
      const rest = strip(v, p, boxed);
      if (rest !== undefined) out[k] = rest;
    } else {
      out[k] = v;
    }
  }
  return Object.keys(out).length ? out : undefined;
}

function* leafPaths(node, prefix = "") {
  if (Array.isArray(node) || isObject(node)) {
    for (const [k, v] of Object.entries(node)) yield* leafPaths(v, prefix ? `${prefix}.${k}` : k);
  } else {
    yield prefix;
  }
}

/** Copy `src` into `target` (objects merged, arrays only as far as `target`'s own). */
function merge(target, src) {
  for (const [k, v] of Object.entries(src || {})) {
    if (Array.isArray(v)) {
      if (Array.isArray(target[k])) target[k].forEach((t, n) => merge(t, v[n]));
    } else if (isObject(v)) {
      target[k] = isObject(target[k]) ? target[k] : {};
      merge(target[k], v);
    } else {
      target[k] = v;
    }
  }
  return target;
}

function setPath(obj, path, v) {
  const keys = path.split(".");
  let node = obj;
  keys.slice(0, -1).forEach((k, n) => {
    node[k] ??= /^\d+$/.test(keys[n + 1]) ? [] : {};
    node = node[k];
  });
  node[keys.at(-1)] = v;
}

/** The spec the boxes describe (an empty box is left out: the library's value or the documented default). */
export function readSpec() {
  const spec = { units: [], couplings: [] };
  const title = $("#cb-title").value.trim();
  if (title) spec.title = title;
  const llt = value($("#cb-front-llt"));
  if (llt !== undefined) spec.front_llt_ratio = llt;
  for (const unit of $$("#cb-units .cb-unit")) {
    const i = Number(unit.dataset.unit);
    spec.units[i] = {
      axle_groups: $$(".cb-group", unit).map(() => ({ tyre: {}, suspension: {} })),
      tare: {},
      payloads: $$(".cb-payload", unit).map((fs) => ({ [WAY]: fs.dataset.kind })),
    };
    merge(spec.units[i], structuredClone(state.extra[i] || {}));
  }
  for (const c of $$("#cb-units .cb-coupling")) spec.couplings[Number(c.dataset.coupling)] = {};
  for (const c of $$("#cb-units [data-cb]")) {
    const v = value(c);
    if (v !== undefined) setPath(spec, c.dataset.cb, v);
  }
  for (const u of spec.units) {
    if (!u.payloads.length) delete u.payloads;
    if (u.deck && !Object.keys(u.deck).length) delete u.deck;
  }
  return spec;
}

/** The coupling a towed unit of `towed` kind is usually joined by to a unit of `towing` kind. */
function couplingFor(towing, towed) {
  if (towed === "dolly" || towed === "full-trailer") return { kind: "pintle" };
  if (towing === "btrain-lead") return { kind: "b-coupling", fifth_wheel: state.library.fifthWheels[0] };
  return { kind: "fifth-wheel", fifth_wheel: state.library.fifthWheels[0] };
}

export const newUnit = (kind) => ({ kind, axle_groups: NEW_GROUPS[kind].map((g) => ({ ...g, tyre: {}, suspension: {} })), tare: {} });

/** From scratch: a tractor and a semitrailer, the boxes empty but for the axles. */
export function scratchSpec() {
  return { units: [newUnit("tractor"), newUnit("semitrailer")], couplings: [couplingFor("tractor", "semitrailer")] };
}

/** A structural edit (a unit or payload added or removed, a kind changed): redraw, and the results are stale. */
function restructure(change) {
  const spec = readSpec();
  change(spec);
  render(spec);
  stale.mark(stale.DEPENDS.vehicle);
}

function onClick(ev) {
  const b = ev.target.closest("button");
  if (!b) return;
  const i = Number(b.dataset.unit);
  if (b.classList.contains("cb-add-payload")) {
    restructure((spec) => {
      spec.units[i].payloads ??= [];
      spec.units[i].payloads.push({ distribution: "uniform" });
    });
  } else if (b.classList.contains("cb-remove-payload")) {
    const k = Number(b.dataset.payload);
    restructure((spec) => spec.units[i].payloads.splice(k, 1));
  } else if (b.classList.contains("cb-remove-unit")) {
    restructure((spec) => {
      spec.units.splice(i, 1);
      spec.couplings.splice(Math.min(i, spec.couplings.length - 1), 1);
    });
  }
}

function addUnit() {
  const kind = $("#cb-add-kind").value;
  restructure((spec) => {
    const last = spec.units.at(-1);
    spec.units.push(newUnit(kind));
    if (last) spec.couplings.push(couplingFor(last.kind, kind));
  });
}

/** Another way of giving a payload's height: the boxes of that way, the previous way's values dropped. */
function onPayloadKindChange(c) {
  const i = Number(c.dataset.unit);
  const k = Number(c.dataset.payload);
  const way = c.value in PAYLOAD_KINDS ? c.value : "deck";
  restructure((spec) => {
    const payload = spec.units[i].payloads[k];
    const keep = PAYLOAD_KINDS[way].fields;
    for (const name of HEIGHT_FIELDS) if (!keep.includes(name)) delete payload[name];
    if (way === "sloped") delete payload.cg_from_kingpin_m; // a sloping deck's CG is its load's centroid
    if (keep.includes("distribution")) payload.distribution ??= "uniform";
    if (way === "tank") payload.tank = isObject(payload.tank) ? payload.tank : { shape: "circular" };
    payload[WAY] = way;
  });
  $(`#${c.id}`)?.focus();
}

function onKindChange(ev) {
  const c = ev.target;
  if (c.matches?.("select[data-payload-kind]")) {
    onPayloadKindChange(c);
    return;
  }
  if (!c.matches?.('select[data-cb$=".kind"]') || !c.dataset.cb.startsWith("units.")) return;
  const i = Number(c.dataset.cb.split(".")[1]);
  restructure((spec) => {
    const u = spec.units[i];
    const want = NEW_GROUPS[u.kind].length;
    u.axle_groups = u.axle_groups.slice(0, want);
    while (u.axle_groups.length < want) u.axle_groups.push({ ...NEW_GROUPS[u.kind][u.axle_groups.length], tyre: {}, suspension: {} });
  });
}

// ------------------------------------------------------------------------------------------ start from

function fillStart() {
  const select = clear($("#cb-start"));
  select.append(el("option", { value: "table15" }, TABLE15_SPEC.title));
  for (const c of state.combinations) select.append(el("option", { value: `preset:${c.id}` }, `${c.title}: the preset's values, unit by unit (${c.id})`));
  select.append(el("option", { value: "scratch" }, "From scratch: a tractor and a semitrailer, empty boxes"));
}

/** The spec a start choice describes. */
export async function startSpec(choice) {
  if (choice === "scratch") return scratchSpec();
  if (choice?.startsWith("preset:")) {
    const id = choice.slice("preset:".length);
    const detail = await api.get(`/v1/combinations/${encodeURIComponent(id)}`);
    return specFromRecord(detail.combination, `Preset ${id}: ${detail.title}`.slice(0, 100)); // the spec's title: at most 100
  }
  return structuredClone(TABLE15_SPEC);
}

async function start() {
  const button = $("#cb-start-button");
  button.disabled = true;
  try {
    render(await startSpec($("#cb-start").value));
    stale.mark(stale.DEPENDS.vehicle);
    $("#cb-start-info").textContent = "The editor now holds the chosen start; change any box, then compute.";
  } catch (err) {
    $("#cb-start-info").textContent = `Could not read the preset: ${err.message}`;
  } finally {
    button.disabled = false;
  }
}

/** A spec from the link, shown when the editor starts. */
export function setPending(spec) {
  state.pending = spec;
}

/** Read the library ids from the OpenAPI document, fill the start choices and draw the first spec. */
export async function init(combinations) {
  const doc = await api.spec();
  const schemas = doc.components?.schemas || {};
  const enumOf = (schema, prop) => (schemas[schema]?.properties?.[prop]?.anyOf || []).find((a) => a.enum)?.enum || [];
  state.library.suspensions = enumOf("RollSuspensionSpec", "type");
  state.library.fifthWheels = enumOf("CouplingSpec", "fifth_wheel");
  state.library.dynUnit = dynamicsFields(schemas.UnitDynamicsSpec);
  state.library.dynGroup = dynamicsFields(schemas.GroupDynamicsSpec);
  state.combinations = combinations || [];
  fillStart();
  render(state.pending || structuredClone(TABLE15_SPEC));
  const editor = $("#cb-editor");
  editor.addEventListener("click", onClick);
  editor.addEventListener("change", onKindChange);
  $("#cb-add").addEventListener("click", addUnit);
  $("#cb-start-button").addEventListener("click", start);
}

// ------------------------------------------------------------------------------------------ building

/** The tyre sizes offered as suggestions: those of the specs shown, and those the service lists with data. */
function suggestSizes(sizes) {
  const list = $("#cb-tyre-sizes");
  const known = new Set($$("option", list).map((o) => o.value));
  for (const s of sizes) if (s && !known.has(s)) list.append(el("option", { value: s }));
}

/** Open the folded boxes an error points at, so it is shown beside its box; an unknown tyre size's refusal lists
 * the sizes the library has data for: they become the size boxes' suggestions. */
function reveal(err) {
  for (const item of err?.problem?.errors || []) {
    const listed = /sizes with data: ([^()]+?) \(or give/.exec(item.message || "");
    if (listed) suggestSizes(listed[1].split(", "));
    const name = String(item.field || "").replace(/\[(\d+)\]/g, ".$1");
    for (const c of $$("#cb-editor [data-field]")) {
      if (c.dataset.field.split(" ").includes(name)) c.closest("details")?.setAttribute("open", "");
    }
  }
}

function builtView(built) {
  const units = table(
    [
      { key: "id", label: "Unit", text: true },
      { key: "kind", label: "Kind", text: true, format: (v) => KINDS[v] || v },
      { key: "mass_kg", label: "Mass [kg]", format: (v) => grouped(v, 0) },
      { key: "cg_height_m", label: "CG height [m]", format: (v) => fmt(v, 3) },
      { key: "sprung_mass_kg", label: "Sprung mass [kg]", format: (v) => grouped(v, 0) },
      { key: "sprung_cg_height_m", label: "Sprung CG height [m]", format: (v) => fmt(v, 3) },
    ],
    built.units,
  );
  const loads = table(
    [
      { key: "unit", label: "Unit", text: true },
      { key: "group", label: "Axle group", text: true },
      { key: "load_kg", label: "Static load [kg]", format: (v) => grouped(v, 0) },
      { key: "per_axle_kg", label: "Per axle [kg]", format: (v) => grouped(v, 0) },
    ],
    built.axle_loads,
  );
  const rows = Object.entries(built.derivation || {}).map(([field, d]) => ({ field, ...d }));
  const derivation = table(
    [
      { key: "field", label: "Record field", text: true, format: (v) => fieldLabel(v) },
      { key: "value", label: "Value", format: (v) => (typeof v === "number" ? num(v, 6) : v ?? "-") },
      { key: "unit", label: "Unit", text: true },
      { key: "method", label: "Method", text: true },
      { key: "source", label: "Source", text: true },
    ],
    rows,
  );
  return [
    el("p", { id: "cb-gross" }, `Built: gross mass ${grouped(built.gross_mass_kg, 0)} kg in ${built.units.length} units.`),
    scroller("Each unit's mass and CG", units),
    scroller("Static axle-group loads", loads),
    el("details", { class: "details" }, el("summary", {}, "Where each value of the model comes from"), scroller("How each record field was obtained", derivation, true)),
    ...(built.notes || []).map((n) => el("p", { class: "hint" }, n)),
  ];
}

/** POST /v1/combinations/build for the editor's spec; shows the built units and loads. */
export async function build(spec) {
  let built;
  try {
    built = await api.post("/v1/combinations/build", { combination_spec: spec });
  } catch (err) {
    reveal(err);
    throw err;
  }
  state.built = built;
  clear($("#cb-result")).append(...builtView(built));
  return built;
}
