//! The replay page (`berry-evolve replay --html out.html`): one self-contained HTML file that
//! animates a trial on a canvas. The trial's JSON-lines trace
//! ([`crate::record::trace::files`], numbers to 4 decimals) is embedded in the page, with
//! inline JavaScript and CSS: no network, no external scripts or fonts.
//!
//! The page precomputes per-tick arrays once, draws the static arena (floor, areas, walls,
//! triggers, teleporters, aversive objects, landmarks, the whole path faintly) into a cached
//! background canvas, and per frame draws only that image plus what changes: doors, food
//! amounts, wanderers and predators, the creatures' recent trail and bodies, and the cursors
//! of the side charts (the brain's outputs and the metabolic vector over the whole trial,
//! drawn once, their value labels in a gutter left of the curves). Beside the arena: a key to
//! the arena's symbols listing only the kinds this world has (written here, from the world's
//! description, so that it needs no script and a test can read it from the file), whiskers,
//! both smell sensors' 8 receptors, food detectors, shock and the retina (when the eye is an
//! input) of the selected creature, and the two charts with their colour keys.
//!
//! Controls: play/pause (space), speed, a range slider to scrub by tick, step −1/+1 (arrow
//! keys). `page.html#tick=N` opens paused at tick N, and the page writes into the hidden
//! `<pre id="status">` the tick, each creature's drawn canvas position and the colour of the
//! canvas pixels there, and the same for the middle of a wall, so that a test can check the
//! drawing against the trace (a reader of the page never sees it).
//!
//! A life of several episodes is one page ([`page_life`]): every episode's trace is embedded,
//! the slider and `#tick=P` run over the life (each episode keeps its own tick 0, so position
//! P is episode e's tick P − (the positions of the episodes before)), and the page loads an
//! episode's world when the position enters it; the label says `episode e / K · tick t / T`.
//! For a plastic brain (the trace's `learning` lines) a strip under the arena shows the
//! followed synapses' weights over the whole life, one line each, with ‖Δw‖ and the gate g
//! per tick in two bands below, the episode starts (dashed), the switches (thick, purple; episodes whose payoffs
//! are exchanged shaded), the selected creature's bites coloured by food type and its shock
//! onsets, and a cursor at the current tick. A fixed brain's page has no strip.

use crate::evo::trace::{EventKind, TrialTrace, WorldDescription};
use crate::record::atomic::write_atomic_with;
use crate::record::trace::files::write_jsonl_to;
use std::io;
use std::path::Path;

/// The page for `trace`, titled `experiment: trial T of generation G`, lived by a brain
/// whose outputs are `outputs` (in order, as
/// [`crate::experiment::Experiment::output_names`] names them).
pub fn page(trace: &TrialTrace, outputs: &[String]) -> io::Result<String> {
    let title = format!(
        "{}: trial {} of generation {}",
        trace.world.experiment, trace.world.trial, trace.world.generation
    );
    page_titled(trace, &title, outputs)
}

/// [`page`] under `title` (the caller names the worlds, e.g. `held-out world 2`, which the
/// trace alone cannot tell).
pub fn page_titled(trace: &TrialTrace, title: &str, outputs: &[String]) -> io::Result<String> {
    page_life(std::slice::from_ref(trace), title, outputs)
}

/// The page of a whole life: `life` holds its episodes in order (one trace each, see
/// [`life_of`]; a single trace for a life of one episode). The slider runs over the life and
/// the page shows the episode the current tick is in; a plastic brain's life adds the strip
/// of its followed weights under the arena (see the module docs).
/// An empty `life` is an error (there is nothing to draw).
pub fn page_life(life: &[TrialTrace], title: &str, outputs: &[String]) -> io::Result<String> {
    if life.is_empty() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "no trial was recorded, so there is no page to draw",
        ));
    }
    let mut data = Vec::new();
    write_jsonl_to(life, Some(4), &mut data)?;
    let data =
        String::from_utf8(data).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))?;
    // Inside a <script> element "</" could end it; "<\/" is the same JSON string.
    let data = data.replace("</", "<\\/");
    let title = escape(title);
    let series = motor_series(outputs);
    let motor_title = escape(&format!(
        "motor outputs ({}) over the trial",
        outputs.join(", ")
    ));
    let motor_keys: String = series
        .iter()
        .map(|s| key(&format!("output-{}", s.name), &swatch(s.colour), s.name))
        .collect();
    let metab_keys: String = FOOD_COLOURS
        .iter()
        .zip(["A", "B", "C", "D"])
        .map(|(c, t)| key(&format!("m-{t}"), &swatch(c), &format!("m {t}")))
        .collect();
    // The fields of the trace's creature rows the script draws, with their colours.
    let motor_js = format!(
        "[{}]",
        series
            .iter()
            .map(|s| format!("[\"{}\",\"{}\"]", s.field, s.colour))
            .collect::<Vec<_>>()
            .join(",")
    );
    Ok(TEMPLATE
        .replace("{{TITLE}}", &title)
        .replace("{{LEGEND}}", &arena_legend(life))
        .replace("{{STRIP}}", &strip(life))
        .replace("{{MOTOR_TITLE}}", &motor_title)
        .replace("{{MOTOR_KEYS}}", &motor_keys)
        .replace("{{METAB_KEYS}}", &metab_keys)
        .replace("{{MOTOR_SERIES}}", &motor_js)
        .replace("{{DATA}}", &data))
}

/// Writes the page for `trace` (lived by a brain with `outputs`) to `path` (atomically).
pub fn write(trace: &TrialTrace, outputs: &[String], path: &Path) -> io::Result<()> {
    let html = page(trace, outputs)?;
    write_atomic_with(path, |w| w.write_all(html.as_bytes()))
}

/// Writes the page of the life `life` under `title` ([`page_life`]) to `path` (atomically).
pub fn write_life(
    life: &[TrialTrace],
    title: &str,
    outputs: &[String],
    path: &Path,
) -> io::Result<()> {
    let html = page_life(life, title, outputs)?;
    write_atomic_with(path, |w| w.write_all(html.as_bytes()))
}

/// The traces of the life that `traces` begins with: its first trace, then the later
/// episodes of the same life (a life of several episodes records one trace per episode).
pub fn life_of(traces: &[TrialTrace]) -> &[TrialTrace] {
    let Some(first) = traces.first() else {
        return traces;
    };
    let later = traces[1..]
        .iter()
        .take_while(|t| {
            t.world.trial == first.world.trial
                && t.world.episode.as_ref().is_some_and(|e| e.episode > 1)
        })
        .count();
    &traces[..1 + later]
}

/// Writes the page for `trace` under `title` ([`page_titled`]) to `path` (atomically).
pub fn write_titled(
    trace: &TrialTrace,
    title: &str,
    outputs: &[String],
    path: &Path,
) -> io::Result<()> {
    let html = page_titled(trace, title, outputs)?;
    write_atomic_with(path, |w| w.write_all(html.as_bytes()))
}

/// The creature body's colour on the page (the test looks for it).
pub const CREATURE_COLOUR: [u8; 3] = [31, 63, 191];

/// Food types A–D, as the canvas draws them (and the metabolic vector's components).
const FOOD_COLOURS: [&str; 4] = ["#d62728", "#1f77b4", "#2ca02c", "#ff7f0e"];

/// One curve of the motor chart: a brain output and the trace field that records it.
struct Series {
    name: &'static str,
    field: &'static str,
    colour: &'static str,
}

/// The curves of the motor chart: one per output the brain has, of those the trace records
/// (every output [`crate::experiment::Experiment::output_names`] can name today).
fn motor_series(outputs: &[String]) -> Vec<Series> {
    const KNOWN: [Series; 3] = [
        Series {
            name: "motor_left",
            field: "left",
            colour: "#1f77b4",
        },
        Series {
            name: "motor_right",
            field: "right",
            colour: "#d62728",
        },
        Series {
            name: "eat",
            field: "eat",
            colour: "#555555",
        },
    ];
    KNOWN
        .into_iter()
        .filter(|s| outputs.iter().any(|o| o == s.name))
        .collect()
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A key entry: a small inline SVG symbol and its words; `kind` names it for tests.
fn key(kind: &str, symbol: &str, text: &str) -> String {
    format!(
        r#"<span class="key" data-kind="{kind}"><svg width="24" height="16" viewBox="-12 -8 24 16" aria-hidden="true">{symbol}</svg>{}</span>"#,
        escape(text)
    )
}

/// A line sample in `colour` (chart keys).
fn swatch(colour: &str) -> String {
    format!(r#"<line x1="-10" y1="0" x2="10" y2="0" stroke="{colour}" stroke-width="3"/>"#)
}

fn rgb(c: [f64; 3]) -> String {
    let b = |x: f64| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("rgb({},{},{})", b(c[0]), b(c[1]), b(c[2]))
}

/// A line symbol like the canvas draws a wall or door.
fn segment(colour: &str, width: f64, dash: &str, opacity: f64) -> String {
    format!(
        r#"<line x1="-10" y1="0" x2="10" y2="0" stroke="{colour}" stroke-width="{width}" stroke-dasharray="{dash}" stroke-opacity="{opacity}" stroke-linecap="round"/>"#
    )
}

/// The key to the arena's symbols: only the kinds the first episode's world has (and the
/// marks of the events the life had), each drawn as the canvas draws it.
fn arena_legend(life: &[TrialTrace]) -> String {
    let mut out = world_keys(&life[0].world);
    out.push_str(&event_keys(life));
    out
}

/// Colours of the followed synapses' lines (the script has the same list).
const SYNAPSE_COLOURS: [&str; 8] = [
    "#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#a6761d", "#e6ab02", "#666666",
];

/// The strip under the arena for a plastic brain's life (empty for a fixed brain): its
/// title, the keys of creature 0's followed synapses and of the marks, and the canvas the
/// script draws.
fn strip(life: &[TrialTrace]) -> String {
    let Some(info) = life[0].learning.first() else {
        return String::new();
    };
    let which = match info.chosen.as_str() {
        "named" => format!("the {} synapses named", info.synapses.len()),
        _ => format!(
            "the {} synapses whose weight moved most over the life",
            info.synapses.len()
        ),
    };
    let title = escape(&format!(
        "plastic weights over the {}: {which}",
        if life.len() > 1 { "life" } else { "trial" }
    ));
    let synapses: String = info
        .synapses
        .iter()
        .zip(SYNAPSE_COLOURS.iter().cycle())
        .map(|(s, c)| key("synapse", &swatch(c), &s.name))
        .collect();
    let mut marks = String::new();
    let episodes: Vec<_> = life
        .iter()
        .filter_map(|t| t.world.episode.as_ref())
        .collect();
    if life.len() > 1 {
        marks.push_str(&key(
            "episode",
            r##"<line x1="0" y1="-7" x2="0" y2="7" stroke="#999" stroke-dasharray="4 3"/>"##,
            "episode start",
        ));
    }
    if episodes.iter().any(|e| e.switched) {
        let kinds = episodes[0].switch_kinds.join(" and ");
        marks.push_str(&key(
            "switch",
            r##"<line x1="0" y1="-7" x2="0" y2="7" stroke="#7b2cbf" stroke-width="2.5"/>"##,
            &format!("switch ({kinds} exchange payoffs)"),
        ));
    }
    if episodes.iter().any(|e| e.exchanged) {
        marks.push_str(&key(
            "exchanged",
            r#"<rect x="-10" y="-6" width="20" height="12" fill="rgba(123,44,191,0.15)"/>"#,
            "payoffs exchanged",
        ));
    }
    let creature = info.creature;
    let mut bitten = [false; 4];
    let mut shocked = false;
    for t in life {
        for e in t.events.iter().filter(|e| e.creature == Some(creature)) {
            match e.event {
                EventKind::Eat => {
                    if let Some(f) = e.target.and_then(|k| t.world.food.get(k)) {
                        bitten[f.food_type.min(3)] = true;
                    }
                }
                EventKind::Shock => shocked = true,
                _ => {}
            }
        }
    }
    for (t, colour) in FOOD_COLOURS.iter().enumerate() {
        if bitten[t] {
            let name = (b'A' + t as u8) as char;
            marks.push_str(&key(
                &format!("bite-{}", name.to_ascii_lowercase()),
                &format!(
                    r#"<line x1="0" y1="-6" x2="0" y2="6" stroke="{colour}" stroke-width="2"/>"#
                ),
                &format!("bite of food {name}"),
            ));
        }
    }
    if shocked {
        marks.push_str(&key(
            "strip-shock",
            r##"<path d="M0,-6 L4,4 L-4,4 z" fill="#ffb703"/>"##,
            "shock onset",
        ));
    }
    marks.push_str(&key("dw-norm", &swatch("#444"), "‖Δw‖ per tick"));
    marks.push_str(&key(
        "gate",
        &swatch("#bb3e03"),
        "gate g = tanh(m/2) per tick",
    ));
    format!(
        r#"<div id="learn"><div class="lbl" id="striplbl">{title}</div><div class="keys" id="synkeys">{synapses}</div><canvas id="strip" width="660" height="250"></canvas><div class="keys" id="stripkeys">{marks}</div></div>"#
    )
}

/// The keys of the kinds of object the world has, and only those.
fn world_keys(w: &WorldDescription) -> String {
    let mut out = String::new();
    let mut add = |kind: &str, symbol: String, text: &str| out.push_str(&key(kind, &symbol, text));
    add(
        "creature",
        r##"<path d="M-10,-5 L-3,-1" stroke="#555" stroke-width="1.5"/><circle cx="0" cy="0" r="5" fill="rgb(31,63,191)"/><path d="M5,0 L10,0" stroke="#000" stroke-width="2"/>"##.into(),
        if w.creatures.len() > 1 {
            "creatures, their recent trails"
        } else {
            "creature, its recent trail"
        },
    );
    for (t, colour) in FOOD_COLOURS.iter().enumerate() {
        if w.food.iter().any(|f| f.food_type.min(3) == t) {
            let name = (b'A' + t as u8) as char;
            add(
                &format!("food-{}", name.to_ascii_lowercase()),
                format!(
                    r##"<circle cx="0" cy="0" r="5.5" fill="#fff" stroke="{colour}" stroke-width="1.3"/><circle cx="0" cy="0" r="3.5" fill="{colour}"/>"##
                ),
                &format!("food {name} (fill = amount)"),
            );
        }
    }
    if !w.aversives.is_empty() {
        add(
            "aversive",
            r#"<circle cx="0" cy="0" r="6" fill="rgba(157,78,221,0.55)"/>"#.into(),
            "aversive object",
        );
    }
    if let Some(wall) = w.walls.iter().find(|x| x.opaque) {
        add("wall", segment(&rgb(wall.colour), 3.5, "none", 1.0), "wall");
    }
    if let Some(wall) = w.walls.iter().find(|x| !x.opaque) {
        add(
            "glass",
            segment(&rgb(wall.colour), 5.0, "7 4", 0.55),
            "glass wall (smell passes)",
        );
    }
    if let Some(door) = w.doors.first() {
        add(
            "door",
            segment(&rgb(door.colour), 6.0, "none", 1.0),
            "door (dotted while open)",
        );
        add(
            "trigger",
            r##"<circle cx="0" cy="0" r="6" fill="rgba(255,179,71,0.3)" stroke="#e07b00" stroke-dasharray="4 3"/>"##.into(),
            "door trigger",
        );
    }
    if !w.teleporters.is_empty() {
        add(
            "teleporter",
            r##"<circle cx="-4" cy="0" r="5" fill="rgba(199,125,255,0.4)" stroke="#7b2cbf"/><path d="M1,0 L10,0" stroke="#7b2cbf" stroke-dasharray="3 2"/>"##.into(),
            "teleporter entry → exit",
        );
    }
    if w.areas.iter().any(|a| a.kind == "safe") {
        add(
            "nest",
            r#"<rect x="-10" y="-6" width="20" height="12" fill="rgba(160,215,150,0.55)"/>"#.into(),
            "safe area (nest)",
        );
    }
    if w.areas.iter().any(|a| a.kind != "safe") {
        add(
            "area",
            r#"<rect x="-10" y="-6" width="20" height="12" fill="rgba(235,220,140,0.55)"/>"#.into(),
            "area",
        );
    }
    if !w.landmarks.is_empty() {
        let star: String = (0..10)
            .map(|k| {
                let a = std::f64::consts::PI / 5.0 * k as f64 - std::f64::consts::FRAC_PI_2;
                let r = if k % 2 == 1 { 3.0 } else { 7.0 };
                format!("{:.1},{:.1} ", r * libm::cos(a), r * libm::sin(a))
            })
            .collect();
        add(
            "landmark",
            format!(
                r##"<polygon points="{}" fill="#f4d35e" stroke="#a07c00"/>"##,
                star.trim_end()
            ),
            "landmark (beacon)",
        );
    }
    if w.actors.iter().any(|a| a.role == "predator") {
        add(
            "predator",
            r##"<circle cx="0" cy="0" r="5" fill="#9b2226"/>"##.into(),
            "ground predator",
        );
    }
    if !w.air_predators.is_empty() {
        add(
            "air-predator",
            r##"<circle cx="0" cy="0" r="7" fill="rgba(187,62,3,0.15)" stroke="#bb3e03"/><rect x="-2" y="-2" width="4" height="4" fill="#bb3e03"/>"##.into(),
            "air predator, strike disc",
        );
    }
    if w.actors.iter().any(|a| a.role == "wanderer") {
        add(
            "wanderer",
            r##"<circle cx="0" cy="0" r="5" fill="#8d99ae"/>"##.into(),
            "wanderer",
        );
    }
    out
}

/// The keys of the marks of the events the life had, and only those.
fn event_keys(life: &[TrialTrace]) -> String {
    let mut out = String::new();
    let mut add = |kind: &str, symbol: String, text: &str| out.push_str(&key(kind, &symbol, text));
    let had = |k: EventKind| life.iter().any(|t| t.events.iter().any(|e| e.event == k));
    if had(EventKind::Eat) {
        add(
            "mark-eat",
            r#"<circle cx="0" cy="0" r="6" fill="none" stroke="rgba(27,158,58,0.5)"/>"#.into(),
            "ate here",
        );
    }
    if had(EventKind::Shock) {
        add(
            "mark-shock",
            r##"<path d="M0,-6 L5,3 L-5,3 z" fill="#ffb703"/>"##.into(),
            "shocked here",
        );
    }
    if had(EventKind::Death) {
        add(
            "mark-death",
            r##"<path d="M-6,-6 L6,6 M6,-6 L-6,6" stroke="#000" stroke-width="3"/>"##.into(),
            "died here",
        );
    }
    out
}

const TEMPLATE: &str = r##"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{{TITLE}}</title>
<style>
body{font-family:sans-serif;font-size:13px;margin:10px;background:#fff;color:#222}
#wrap{display:flex;gap:14px;align-items:flex-start}
#main{display:flex;flex-direction:column;gap:4px;align-items:flex-start}
#side{display:flex;flex-direction:column;gap:6px;min-width:380px}
canvas{display:block}
#arena{border:1px solid #ccc}
.row{display:flex;gap:8px;align-items:center;flex-wrap:wrap}
h1{font-size:17px;margin:0 0 6px 0}
.lbl{color:#555;font-size:12px;margin-top:4px}
#status{display:none}
.keys{display:flex;flex-wrap:wrap;gap:2px 12px;font-size:12px;color:#333}
.key{display:inline-flex;align-items:center;gap:4px;white-space:nowrap}
.key svg{flex:none}
#legend{display:grid;grid-template-columns:repeat(2,minmax(0,1fr));gap:1px 10px;font-size:12px;color:#333;max-width:380px}
button{min-width:34px}
</style></head><body>
<h1>{{TITLE}}</h1>
<div class="row" id="controls">
<button id="play" title="play / pause (space)">play</button>
<button id="back" title="one tick back (left arrow)">&minus;1</button>
<button id="fwd" title="one tick on (right arrow)">+1</button>
<label>speed <select id="speed"><option value="0.25">¼×</option><option value="0.5">½×</option><option value="1" selected>1×</option><option value="2">2×</option><option value="4">4×</option><option value="8">8×</option><option value="16">16×</option><option value="64">64×</option></select></label>
<input id="scrub" type="range" min="0" max="1" value="0" style="width:360px">
<span id="ticklabel"></span>
<label id="whichlabel">creature <select id="which"></select></label>
</div>
<div id="wrap">
<div id="main"><canvas id="arena"></canvas>{{STRIP}}</div>
<div id="side">
<div class="lbl">in the arena</div><div id="legend">{{LEGEND}}</div>
<div class="lbl">whiskers (left, right) · food detectors A–D · shock</div><canvas id="touch" width="380" height="34"></canvas>
<div class="lbl">smell receptors 1–8, left sensor then right</div><canvas id="smell" width="380" height="60"></canvas>
<div class="lbl" id="eyelbl">retina</div><canvas id="eye" width="380" height="30"></canvas>
<div class="lbl" id="motorlbl">{{MOTOR_TITLE}}</div><div class="keys" id="motorkeys">{{MOTOR_KEYS}}</div><canvas id="motor" width="380" height="90"></canvas>
<div class="lbl" id="metablbl">metabolic vector m (A–D) over the trial</div><div class="keys" id="metabkeys">{{METAB_KEYS}}</div><canvas id="metab" width="380" height="90"></canvas>
<div class="lbl" id="info"></div>
</div></div>
<pre id="status" hidden style="display:none"></pre>
<script type="application/x-ndjson" id="trace">
{{DATA}}
</script>
<script>
"use strict";
(function(){
const lines=document.getElementById("trace").textContent.split("\n").filter(l=>l.trim().length);
// The life's episodes (one for a life of one episode), each from its world line on. The page
// shows one episode at a time; the slider and #tick=P run over the life: position P is tick
// P - OFF[e] of episode e (each episode has its own tick 0).
const EP=[];
for(const l of lines){const r=JSON.parse(l);if(r.type==="world")EP.push({W:r,ticks:[],outcome:null,learning:null});else{const e=EP[EP.length-1];if(r.type==="tick")e.ticks.push(r);else if(r.type==="outcome")e.outcome=r;else if(r.type==="learning")e.learning=r;}}
const OFF=[];let P=0;for(const e of EP){OFF.push(P);P+=e.ticks.length+1;}
const LAST=P-1;
let epi=-1,W=null,outcome=null,ticks=[],T=0,N=0;
let cx,cy,ch,alive,crow,actorKeys,ax,ay,changes,doorOpen,marks,scale,cw,chh,walls,wallIndex;
const FOOD=["#d62728","#1f77b4","#2ca02c","#ff7f0e"],CREATURE="rgb(31,63,191)";
const rgb=c=>"rgb("+c.map(x=>Math.round(Math.max(0,Math.min(1,x))*255)).join(",")+")";
const PX=640,PAD=10;
const X=x=>PAD+x*scale,Y=y=>PAD+y*scale;
const arena=document.getElementById("arena");
const g=arena.getContext("2d",{willReadFrequently:true});
const bg=document.createElement("canvas");
function akey(kind,index){return kind+":"+index;}
function amountAt(k,t){const c=changes[k];let lo=0,hi=c.length-1;while(lo<hi){const m=(lo+hi+1)>>1;if(c[m][0]<=t)lo=m;else hi=m-1;}return c[lo][1];}
// Episode k: its per-tick arrays (index 0 = its start) and its cached background.
function load(k){epi=k;const E=EP[k];W=E.W;outcome=E.outcome;ticks=E.ticks;T=ticks.length;N=W.creatures.length;
cx=[];cy=[];ch=[];alive=[];
for(let i=0;i<N;i++){cx.push(new Float64Array(T+1));cy.push(new Float64Array(T+1));ch.push(new Float64Array(T+1));alive.push(new Uint8Array(T+1));
 cx[i][0]=W.creatures[i].position[0];cy[i][0]=W.creatures[i].position[1];ch[i][0]=W.creatures[i].heading;alive[i][0]=1;}
crow=[];for(let i=0;i<N;i++)crow.push(new Array(T+1).fill(null));
for(let t=1;t<=T;t++){const k=ticks[t-1];for(const c of k.creatures){const i=c.creature;cx[i][t]=c.x;cy[i][t]=c.y;ch[i][t]=c.heading;alive[i][t]=c.alive?1:0;crow[i][t]=c;}}
for(let i=0;i<N;i++)crow[i][0]=crow[i][1];
// Actors: wanderers, predators, air predators.
actorKeys=[];ax={};ay={};
W.actors.forEach((a,n)=>{const kind=a.role,index=W.actors.slice(0,n).filter(b=>b.role===kind).length;const key=akey(kind,index);actorKeys.push([key,kind,a.colour]);ax[key]=new Float64Array(T+1);ay[key]=new Float64Array(T+1);ax[key][0]=a.start.position[0];ay[key][0]=a.start.position[1];});
W.air_predators.forEach((a,k)=>{const key=akey("air_predator",k);actorKeys.push([key,"air_predator",[0.73,0.24,0.01],a.strike_radius]);ax[key]=new Float64Array(T+1);ay[key]=new Float64Array(T+1);ax[key][0]=a.position[0];ay[key][0]=a.position[1];});
for(let t=1;t<=T;t++)for(const a of ticks[t-1].actors){const key=akey(a.kind,a.index);if(ax[key]){ax[key][t]=a.x;ay[key][t]=a.y;}}
// Food amounts: the changes of each object, found by binary search.
changes=W.food.map(f=>[[0,f.amount]]);
for(let t=1;t<=T;t++)for(const o of ticks[t-1].objects)changes[o.object].push([t,o.amount]);
// Doors: open state per tick from the events.
doorOpen=W.doors.map(()=>new Uint8Array(T+1));
marks=[];
for(let t=1;t<=T;t++){for(let d=0;d<W.doors.length;d++)doorOpen[d][t]=doorOpen[d][t-1];
 for(const e of ticks[t-1].events){if(e.event==="door_open")doorOpen[e.target][t]=1;else if(e.event==="door_close")doorOpen[e.target][t]=0;else marks.push([t,e]);}}
// Drawing frame: LU to canvas pixels.
scale=PX/Math.max(W.arena[0],W.arena[1]);
cw=Math.round(W.arena[0]*scale+2*PAD);chh=Math.round(W.arena[1]*scale+2*PAD);
if(arena.width!==cw||arena.height!==chh){arena.width=cw;arena.height=chh;}
bg.width=cw;bg.height=chh;
(function drawBackground(){const b=bg.getContext("2d");b.fillStyle="#ffffff";b.fillRect(0,0,cw,chh);
 b.fillStyle="rgb(247,247,242)";b.fillRect(X(0),Y(0),W.arena[0]*scale,W.arena[1]*scale);
 for(const a of W.areas){b.fillStyle=a.kind==="safe"?"rgba(160,215,150,0.55)":"rgba(235,220,140,0.55)";b.fillRect(X(a.lo[0]),Y(a.lo[1]),(a.hi[0]-a.lo[0])*scale,(a.hi[1]-a.lo[1])*scale);}
 for(const d of W.doors){b.beginPath();b.arc(X(d.trigger[0]),Y(d.trigger[1]),Math.max(3,d.trigger_radius*scale),0,2*Math.PI);b.fillStyle="rgba(255,179,71,0.3)";b.fill();b.setLineDash([4,3]);b.strokeStyle="#e07b00";b.stroke();b.setLineDash([]);}
 for(const t of W.teleporters){b.beginPath();b.arc(X(t.entry[0]),Y(t.entry[1]),Math.max(3,t.radius*scale),0,2*Math.PI);b.fillStyle="rgba(199,125,255,0.4)";b.fill();b.strokeStyle="#7b2cbf";b.stroke();
  b.setLineDash([6,4]);b.beginPath();b.moveTo(X(t.entry[0]),Y(t.entry[1]));b.lineTo(X(t.exit[0]),Y(t.exit[1]));b.stroke();b.setLineDash([]);b.beginPath();b.arc(X(t.exit[0]),Y(t.exit[1]),3,0,2*Math.PI);b.stroke();}
 for(const a of W.aversives){b.beginPath();b.arc(X(a.position[0]),Y(a.position[1]),Math.max(3,a.radius*scale),0,2*Math.PI);b.fillStyle="rgba(157,78,221,0.55)";b.fill();}
 for(const l of W.landmarks){const x=Math.max(0,Math.min(W.arena[0],l[0])),y=Math.max(0,Math.min(W.arena[1],l[1]));b.fillStyle="#f4d35e";b.strokeStyle="#a07c00";b.beginPath();for(let k=0;k<10;k++){const a=Math.PI/5*k-Math.PI/2,r=k%2?4:9;b.lineTo(X(x)+r*Math.cos(a),Y(y)+r*Math.sin(a));}b.closePath();b.fill();b.stroke();}
 // The whole path, faint.
 b.lineWidth=1;b.strokeStyle="rgba(31,63,191,0.18)";
 for(let i=0;i<N;i++){b.beginPath();b.moveTo(X(cx[i][0]),Y(cy[i][0]));for(let t=1;t<=T;t++){const jump=Math.hypot(cx[i][t]-cx[i][t-1],cy[i][t]-cy[i][t-1])>30;if(jump)b.moveTo(X(cx[i][t]),Y(cy[i][t]));else b.lineTo(X(cx[i][t]),Y(cy[i][t]));}b.stroke();}
 b.lineCap="round";
 for(const w of W.walls){b.strokeStyle=rgb(w.colour);b.lineWidth=w.opaque?3.5:5;if(!w.opaque){b.globalAlpha=0.55;b.setLineDash([7,4]);}b.beginPath();b.moveTo(X(w.from[0]),Y(w.from[1]));b.lineTo(X(w.to[0]),Y(w.to[1]));b.stroke();b.globalAlpha=1;b.setLineDash([]);}
 b.lineCap="butt";})();
// The wall whose middle the status reports: the first opaque interior wall, else the first wall.
walls=W.walls;const boundary=walls.length>=4&&walls[0].from[0]===0&&walls[0].from[1]===0?4:0;
wallIndex=walls.findIndex((w,k)=>k>=boundary&&w.opaque);if(wallIndex<0)wallIndex=walls.findIndex(w=>w.opaque);if(wallIndex<0)wallIndex=0;}
load(0);
// Side charts, drawn once; the cursor per frame. The value labels stand in a gutter left of
// the plotting area, so that no curve runs over them.
const GUTTER=44;
const fmt=v=>{const a=Math.abs(v);return a===0?"0":(a>=1e4||a<1e-2)?v.toExponential(1):String(+v.toPrecision(3));};
function chart(id,series,colours,lo,hi){const c=document.getElementById(id),x=c.getContext("2d"),w=c.width,h=c.height;const img=document.createElement("canvas");img.width=w;img.height=h;const b=img.getContext("2d");
 b.fillStyle="#ffffff";b.fillRect(0,0,w,h);b.fillStyle="#fafafa";b.fillRect(GUTTER,0,w-GUTTER,h);b.strokeStyle="#ddd";b.strokeRect(GUTTER+0.5,0.5,w-GUTTER-1,h-1);if(hi<=lo)hi=lo+1;
 const px=t=>GUTTER+1+t/Math.max(1,T)*(w-GUTTER-3);
 const y=v=>h-3-(v-lo)/(hi-lo)*(h-6);
 b.fillStyle="#555";b.font="10px sans-serif";b.textAlign="right";b.textBaseline="middle";
 const label=(v,at)=>{b.fillText(fmt(v),GUTTER-4,at);b.strokeStyle="#bbb";b.beginPath();b.moveTo(GUTTER-2,Math.round(y(v))+0.5);b.lineTo(GUTTER+1,Math.round(y(v))+0.5);b.stroke();};
 label(hi,7);label(lo,h-7);
 if(lo<0&&hi>0){b.strokeStyle="#ccc";b.beginPath();b.moveTo(GUTTER,Math.round(y(0))+0.5);b.lineTo(w,Math.round(y(0))+0.5);b.stroke();if(y(0)>18&&y(0)<h-18)label(0,y(0));}
 series.forEach((s,k)=>{b.strokeStyle=colours[k];b.lineWidth=1;b.beginPath();for(let t=0;t<=T;t++){if(t===0)b.moveTo(px(t),y(s[t]));else b.lineTo(px(t),y(s[t]));}b.stroke();});
 return t=>{x.drawImage(img,0,0);const p=Math.round(px(t))+0.5;x.strokeStyle="#000";x.beginPath();x.moveTo(p,0);x.lineTo(p,h);x.stroke();};}
let cursorMotor=null,cursorMetab=null;
// The brain's outputs the trace records: [field of the creature row, colour] (the page's keys
// name them).
const MOTOR={{MOTOR_SERIES}};
function buildCharts(i){const get=f=>{const a=new Float64Array(T+1);for(let t=0;t<=T;t++){const c=crow[i][t];a[t]=c?f(c):0;}return a;};
 const motor=MOTOR.map(([f])=>get(c=>c[f]));let lo=0,hi=0;for(const s of motor)for(const v of s){lo=Math.min(lo,v);hi=Math.max(hi,v);}
 cursorMotor=chart("motor",motor,MOTOR.map(s=>s[1]),Math.min(lo,-0.01),Math.max(hi,0.01));
 const m=[0,1,2,3].map(k=>get(c=>c.metabolism[k]));let mh=0;for(const s of m)for(const v of s)mh=Math.max(mh,v);
 cursorMetab=chart("metab",m,FOOD,0,Math.max(mh,1e-3));}
const inputs=W.inputs,idx=n=>inputs.indexOf(n);
const smellIdx=[];for(const side of["left","right"])for(let k=1;k<=8;k++)smellIdx.push(idx("smell_"+side+"_"+k));
const eyeCols=[];let eyeRows=0;for(let k=0;k<inputs.length;k++){const m=/^eye_r_(\d+)_(\d+)$/.exec(inputs[k]);if(m){eyeRows=Math.max(eyeRows,+m[1]+1);eyeCols.push([+m[1],+m[2],k]);}}
function bars(id,vals,labels){const c=document.getElementById(id),x=c.getContext("2d");x.fillStyle="#fff";x.fillRect(0,0,c.width,c.height);const n=vals.length,bw=(c.width-10)/n;
 vals.forEach((v,k)=>{const h=(c.height-14)*Math.max(0,Math.min(1,v));x.fillStyle=k<8?"#e07b00":"#7b2cbf";x.fillRect(5+k*bw+1,c.height-12-h,bw-2,h);x.strokeStyle="#ccc";x.strokeRect(5+k*bw+1.5,1.5,bw-3,c.height-14);x.fillStyle="#555";x.font="9px sans-serif";x.fillText(labels[k],5+k*bw+bw/2-3,c.height-2);});}
function boxes(vals,labels){const c=document.getElementById("touch"),x=c.getContext("2d");x.fillStyle="#fff";x.fillRect(0,0,c.width,c.height);
 vals.forEach((v,k)=>{const px=6+k*52;x.fillStyle=v?(k===6?"#ffb703":k>=2?FOOD[k-2]:"#222"):"#eee";x.fillRect(px,4,44,16);x.strokeStyle="#999";x.strokeRect(px+0.5,4.5,44,16);x.fillStyle="#333";x.font="10px sans-serif";x.fillText(labels[k],px+2,31);});}
function eye(c0){const c=document.getElementById("eye"),x=c.getContext("2d");x.fillStyle="#fff";x.fillRect(0,0,c.width,c.height);
 if(!eyeCols.length){x.fillStyle="#888";x.font="11px sans-serif";x.fillText("no eye input",4,18);return;}
 const cols=1+Math.max(...eyeCols.map(e=>e[1])),pw=Math.min(20,(c.width-8)/cols),ph=Math.min(20,(c.height-4)/eyeRows);
 for(const [r,col,k] of eyeCols){const v=[c0.inputs[k],c0.inputs[k+1],c0.inputs[k+2]];x.fillStyle=rgb(v);x.fillRect(4+col*pw,2+r*ph,pw-1,ph-1);}}
// A plastic brain's strip (only when the page has one): the followed synapses' weights over
// the whole life, one line each, ‖Δw‖ per tick in a band below, the episodes (exchanged ones
// shaded), switches, the creature's bites (by food type) and shock onsets; a cursor per frame.
const stripEl=document.getElementById("strip");let cursorStrip=null;
const SYN=["#1b9e77","#d95f02","#7570b3","#e7298a","#66a61e","#a6761d","#e6ab02","#666666"];
function buildStrip(i){if(!stripEl)return;const info=e=>EP[e].learning&&EP[e].learning.creatures.find(c=>c.creature===i);const L=info(0);
 const c=stripEl,x=c.getContext("2d");c.width=Math.max(480,arena.width);const w=c.width,h=c.height;document.getElementById("learn").style.maxWidth=w+"px";
 const keys=document.getElementById("synkeys");
 if(!L){cursorStrip=null;x.fillStyle="#fff";x.fillRect(0,0,w,h);x.fillStyle="#888";x.font="11px sans-serif";x.fillText("creature "+i+"'s brain is not plastic",GUTTER+4,20);if(keys)keys.textContent="";return;}
 const K=L.synapses.length,vals=[],dn=new Float64Array(P),gate=new Float64Array(P);for(let k=0;k<K;k++)vals.push(new Float64Array(P));
 if(keys)keys.innerHTML=L.synapses.map((s,k)=>'<span class="key" data-kind="synapse"><svg width="24" height="16" viewBox="-12 -8 24 16" aria-hidden="true"><line x1="-10" y1="0" x2="10" y2="0" stroke="'+SYN[k%SYN.length]+'" stroke-width="3"/></svg>'+s.name+'</span>').join("");
 let prev=L.start.slice();
 EP.forEach((E,e)=>{const o=OFF[e],li=info(e);if(li)prev=li.start.slice();for(let k=0;k<K;k++)vals[k][o]=prev[k];
  E.ticks.forEach((tk,t)=>{const r=tk.learning&&tk.learning.find(l=>l.creature===i);if(r){prev=r.weights;dn[o+t+1]=r.dw_norm;gate[o+t+1]=r.g;}for(let k=0;k<K;k++)vals[k][o+t+1]=prev[k];});});
 let lo=Infinity,hi=-Infinity;for(const v of vals)for(const a of v){lo=Math.min(lo,a);hi=Math.max(hi,a);}if(!(hi>lo)){lo-=0.5;hi+=0.5;}const pad=(hi-lo)*0.06;lo-=pad;hi+=pad;
 let dmax=0;for(const a of dn)dmax=Math.max(dmax,a);
 const img=document.createElement("canvas");img.width=w;img.height=h;const b=img.getContext("2d");
 const TOP=14,BAND=30,MARK=16,H1=h-TOP-2*BAND-MARK-8;const px=p=>GUTTER+1+p/Math.max(1,LAST)*(w-GUTTER-3);const y=v=>TOP+H1-(v-lo)/(hi-lo)*H1;
 b.fillStyle="#fff";b.fillRect(0,0,w,h);
 // Episodes: exchanged ones shaded, boundaries dashed, switches thick, numbers on top.
 EP.forEach((E,e)=>{const ep=E.W.episode,x0=px(OFF[e]),x1=px(OFF[e]+E.ticks.length);
  if(ep&&ep.exchanged){b.fillStyle="rgba(123,44,191,0.08)";b.fillRect(x0,TOP,x1-x0,H1);}
  if(e>0){b.strokeStyle=ep&&ep.switched?"#7b2cbf":"#999";b.lineWidth=ep&&ep.switched?2.5:1;b.setLineDash(ep&&ep.switched?[]:[4,3]);b.beginPath();b.moveTo(Math.round(x0)+0.5,TOP-2);b.lineTo(Math.round(x0)+0.5,h-2);b.stroke();b.setLineDash([]);b.lineWidth=1;}
  if(EP.length>1){b.fillStyle=ep&&ep.switched?"#7b2cbf":"#666";b.font="10px sans-serif";b.textAlign="left";b.textBaseline="alphabetic";b.fillText((ep&&ep.switched?"switch · ":"")+"ep "+(e+1),x0+3,TOP-3);}});
 b.strokeStyle="#ddd";b.strokeRect(GUTTER+0.5,TOP+0.5,w-GUTTER-1,H1);
 b.fillStyle="#555";b.font="10px sans-serif";b.textAlign="right";b.textBaseline="middle";
 b.fillText(fmt(hi),GUTTER-4,TOP+6);b.fillText(fmt(lo),GUTTER-4,TOP+H1-6);
 if(lo<0&&hi>0){b.strokeStyle="#ccc";b.beginPath();b.moveTo(GUTTER,Math.round(y(0))+0.5);b.lineTo(w,Math.round(y(0))+0.5);b.stroke();b.fillText("0",GUTTER-4,y(0));}
 vals.forEach((v,k)=>{b.strokeStyle=SYN[k%SYN.length];b.lineWidth=1.3;b.beginPath();EP.forEach((E,e)=>{const o=OFF[e];for(let t=0;t<=E.ticks.length;t++){const p=o+t;if(t===0)b.moveTo(px(p),y(v[p]));else b.lineTo(px(p),y(v[p]));}});b.stroke();});
 // Bites (coloured by the food's main type) and shock onsets of this creature.
 const MY=TOP+H1+4;
 EP.forEach((E,e)=>E.ticks.forEach((tk,t)=>{for(const ev of tk.events){if(ev.creature!==i)continue;const p=px(OFF[e]+t+1);
  if(ev.event==="eat"){const f=E.W.food[ev.target];b.strokeStyle=FOOD[Math.min(3,f?f.food_type:0)];b.lineWidth=2;b.beginPath();b.moveTo(p,MY);b.lineTo(p,MY+MARK-4);b.stroke();b.lineWidth=1;}
  else if(ev.event==="shock"){b.fillStyle="#ffb703";b.beginPath();b.moveTo(p,MY);b.lineTo(p+4,MY+MARK-4);b.lineTo(p-4,MY+MARK-4);b.fill();}}}));
 b.fillStyle="#555";b.textAlign="right";b.fillText("events",GUTTER-4,MY+MARK/2-2);
 // ‖Δw‖ per tick.
 const BY=MY+MARK+2;b.fillStyle="#fafafa";b.fillRect(GUTTER,BY,w-GUTTER,BAND);b.strokeStyle="#ddd";b.strokeRect(GUTTER+0.5,BY+0.5,w-GUTTER-1,BAND-1);
 b.fillStyle="#555";b.fillText("‖Δw‖",GUTTER-4,BY+BAND/2);b.textAlign="left";b.fillText("max "+fmt(dmax),GUTTER+4,BY+7);
 if(dmax>0){b.strokeStyle="#444";b.beginPath();for(let p=0;p<P;p++){const v=BY+BAND-2-dn[p]/dmax*(BAND-4);if(p===0)b.moveTo(px(p),v);else b.lineTo(px(p),v);}b.stroke();}
 // The gate g = tanh(m/2) per tick, in [-1, 1] (1 all along for a Hebbian rule).
 const GY=BY+BAND+2,gy=v=>GY+BAND/2-v*(BAND/2-2);b.fillStyle="#fafafa";b.fillRect(GUTTER,GY,w-GUTTER,BAND);b.strokeStyle="#ddd";b.strokeRect(GUTTER+0.5,GY+0.5,w-GUTTER-1,BAND-1);
 b.strokeStyle="#ccc";b.beginPath();b.moveTo(GUTTER,Math.round(gy(0))+0.5);b.lineTo(w,Math.round(gy(0))+0.5);b.stroke();
 b.fillStyle="#555";b.textAlign="right";b.fillText("g",GUTTER-4,GY+BAND/2);b.textAlign="left";b.fillText("±1",GUTTER+4,GY+7);
 b.strokeStyle="#bb3e03";b.beginPath();for(let p=1;p<P;p++){const v=gy(gate[p]);if(p===1)b.moveTo(px(p),v);else b.lineTo(px(p),v);}b.stroke();
 cursorStrip=p=>{x.drawImage(img,0,0);const q=Math.round(px(p))+0.5;x.strokeStyle="#000";x.beginPath();x.moveTo(q,TOP);x.lineTo(q,h);x.stroke();
  const d=x.getImageData(Math.floor(q),h-3,1,1).data;stripStatus="strip cursor at "+q.toFixed(1)+" of "+w+" for position "+p+" of "+LAST+" pixel "+d[0]+","+d[1]+","+d[2];};}
let stripStatus="";
// State.
let tick=0,playing=false,speed=1,acc=0,which=0,last=null;
const scrub=document.getElementById("scrub");scrub.max=LAST;
const sel=document.getElementById("which");for(let i=0;i<N;i++){const o=document.createElement("option");o.value=i;o.textContent=i;sel.appendChild(o);}
if(N<2)document.getElementById("whichlabel").style.display="none";
sel.onchange=()=>{which=+sel.value;buildCharts(which);buildStrip(which);draw();};
buildCharts(0);buildStrip(0);
function draw(){g.drawImage(bg,0,0);const t=tick;
 g.lineCap="round";
 W.doors.forEach((d,k)=>{g.strokeStyle=rgb(d.colour);if(doorOpen[k][t]){g.lineWidth=2;g.setLineDash([2,5]);}else{g.lineWidth=6;}g.beginPath();g.moveTo(X(d.from[0]),Y(d.from[1]));g.lineTo(X(d.to[0]),Y(d.to[1]));g.stroke();g.setLineDash([]);});
 g.lineCap="butt";
 W.food.forEach((f,k)=>{const a=amountAt(k,t),cap=f.capacity.reduce((p,q)=>p+q,0),frac=cap>0?Math.max(0,Math.min(1,a.reduce((p,q)=>p+q,0)/cap)):0,r=Math.max(3.5,f.radius*scale),col=FOOD[Math.min(3,f.food_type)];
  g.beginPath();g.arc(X(f.position[0]),Y(f.position[1]),r,0,2*Math.PI);g.fillStyle="#fff";g.fill();g.strokeStyle=col;g.lineWidth=1.3;g.stroke();if(frac>0){g.beginPath();g.arc(X(f.position[0]),Y(f.position[1]),r*Math.sqrt(frac),0,2*Math.PI);g.fillStyle=col;g.fill();}});
 for(const [key,kind,colour,strike] of actorKeys){const x=X(ax[key][t]),y=Y(ay[key][t]);
  if(kind==="air_predator"){g.beginPath();g.arc(x,y,strike*scale,0,2*Math.PI);g.fillStyle="rgba(187,62,3,0.15)";g.fill();g.strokeStyle="#bb3e03";g.stroke();g.fillStyle="#bb3e03";g.fillRect(x-2,y-2,4,4);}
  else{g.beginPath();g.arc(x,y,Math.max(3,W.creature_radius*scale),0,2*Math.PI);g.fillStyle=kind==="predator"?"#9b2226":"#8d99ae";g.fill();}}
 // Marks of events so far (the last 400 ticks).
 for(const [mt,e] of marks){if(mt>t||mt<t-400)continue;const x=X(e.x),y=Y(e.y);
  if(e.event==="eat"){g.strokeStyle="rgba(27,158,58,0.5)";g.lineWidth=1;g.beginPath();g.arc(x,y,6,0,2*Math.PI);g.stroke();}
  else if(e.event==="shock"){g.fillStyle="#ffb703";g.beginPath();g.moveTo(x,y-6);g.lineTo(x+5,y+3);g.lineTo(x-5,y+3);g.fill();}
  else if(e.event==="death"){g.strokeStyle="#000";g.lineWidth=3;g.beginPath();g.moveTo(x-6,y-6);g.lineTo(x+6,y+6);g.moveTo(x+6,y-6);g.lineTo(x-6,y+6);g.stroke();}}
 g.lineWidth=1;
 const r=Math.max(4,W.creature_radius*scale);
 for(let i=0;i<N;i++){
  // The recent trail, coloured by age.
  g.lineWidth=2;const from=Math.max(1,t-300);
  for(let s=from;s<=t;s++){if(Math.hypot(cx[i][s]-cx[i][s-1],cy[i][s]-cy[i][s-1])>30)continue;const a=(s-from)/Math.max(1,t-from);g.strokeStyle="rgba(31,63,191,"+(0.15+0.7*a).toFixed(3)+")";g.beginPath();g.moveTo(X(cx[i][s-1]),Y(cy[i][s-1]));g.lineTo(X(cx[i][s]),Y(cy[i][s]));g.stroke();}
  const x=X(cx[i][t]),y=Y(cy[i][t]),h=ch[i][t],c=crow[i][t];
  // Whiskers (red while touching), the body, the heading outside it.
  g.lineWidth=1.5;for(const [side,sgn] of[[0,-1],[1,1]]){const a=h+sgn*W.whisker_angle,l=W.whisker_length*scale;g.strokeStyle=c&&c.whiskers[side]?"#e00":"#555";g.beginPath();g.moveTo(x,y);g.lineTo(x+Math.max(l,r+2)*Math.cos(a),y+Math.max(l,r+2)*Math.sin(a));g.stroke();}
  g.beginPath();g.arc(x,y,r,0,2*Math.PI);g.fillStyle=alive[i][t]?CREATURE:"#888";g.fill();
  g.strokeStyle="#000";g.lineWidth=2;g.beginPath();g.moveTo(x+r*Math.cos(h),y+r*Math.sin(h));g.lineTo(x+(r+6)*Math.cos(h),y+(r+6)*Math.sin(h));g.stroke();g.lineWidth=1;
  if(c&&c.shock){g.strokeStyle="#ffb703";g.lineWidth=2;g.beginPath();g.arc(x,y,r+3,0,2*Math.PI);g.stroke();g.lineWidth=1;}}
 // Side panel for the selected creature.
 const c=crow[which][Math.max(1,t)];
 if(c){boxes([c.whiskers[0],c.whiskers[1],c.food[0],c.food[1],c.food[2],c.food[3],c.shock],["whisk L","whisk R","food A","food B","food C","food D","shock"]);
  if(smellIdx.every(k=>k>=0))bars("smell",smellIdx.map(k=>c.inputs[k]),["1","2","3","4","5","6","7","8","1","2","3","4","5","6","7","8"]);
  else{const sc=document.getElementById("smell").getContext("2d");sc.fillStyle="#fff";sc.fillRect(0,0,380,60);sc.fillStyle="#888";sc.font="11px sans-serif";sc.fillText("smell is not an input of this brain",4,30);}
  eye(c);}
 cursorMotor(t);cursorMetab(t);if(cursorStrip)cursorStrip(OFF[epi]+t);
 scrub.value=OFF[epi]+t;document.getElementById("ticklabel").textContent=(EP.length>1?"episode "+(epi+1)+" / "+EP.length+" · ":"")+"tick "+t+" / "+T;
 const o=outcome&&outcome.creatures[which];
 document.getElementById("info").textContent=(c?"m = ["+c.metabolism.map(v=>v.toFixed(2)).join(", ")+"], travelled "+c.travelled.toFixed(0)+" LU":"")+(o?(EP.length>1?" · episode score ":" · trial score ")+o.score.toFixed(4):"");
 status();}
function pixel(x,y){const d=g.getImageData(Math.floor(x),Math.floor(y),1,1).data;return d[0]+","+d[1]+","+d[2];}
function status(){const t=tick,lines=["tick "+t,"scale "+scale+" offset "+PAD];
 for(let i=0;i<N;i++){const x=X(cx[i][t]),y=Y(cy[i][t]);lines.push("creature "+i+" at "+x.toFixed(2)+","+y.toFixed(2)+" pixel "+pixel(x,y)+" alive "+alive[i][t]);}
 const w=walls[wallIndex];if(w){const mx=(w.from[0]+w.to[0])/2,my=(w.from[1]+w.to[1])/2;lines.push("wall "+wallIndex+" at "+X(mx).toFixed(2)+","+Y(my).toFixed(2)+" pixel "+pixel(X(mx),Y(my))+" colour "+rgb(w.colour));}
 if(EP.length>1)lines.push("episode "+(epi+1)+" of "+EP.length+" life position "+(OFF[epi]+t));
 if(cursorStrip)lines.push(stripStatus);
 document.getElementById("status").textContent=lines.join("\n");}
// Position p of the life: its episode (loaded when another), then the tick within it.
function setPos(p){p=Math.max(0,Math.min(LAST,p|0));let k=EP.length-1;while(k>0&&OFF[k]>p)k--;if(k!==epi){load(k);buildCharts(which);}tick=p-OFF[k];draw();}
const pos=()=>OFF[epi]+tick;
document.getElementById("play").onclick=()=>{playing=!playing;document.getElementById("play").textContent=playing?"pause":"play";if(playing){if(pos()>=LAST)setPos(0);last=null;requestAnimationFrame(frame);}};
document.getElementById("back").onclick=()=>{playing=false;document.getElementById("play").textContent="play";setPos(pos()-1);};
document.getElementById("fwd").onclick=()=>{playing=false;document.getElementById("play").textContent="play";setPos(pos()+1);};
document.getElementById("speed").onchange=e=>{speed=+e.target.value;};
scrub.oninput=()=>setPos(+scrub.value);
document.addEventListener("keydown",e=>{if(e.key===" "){e.preventDefault();document.getElementById("play").click();}else if(e.key==="ArrowLeft")document.getElementById("back").click();else if(e.key==="ArrowRight")document.getElementById("fwd").click();});
// 30 ticks a second at 1×.
function frame(now){if(!playing)return;if(last!==null){acc+=(now-last)/1000*30*speed;const n=Math.floor(acc);if(n>0){acc-=n;setPos(pos()+n);}}last=now;if(pos()>=LAST){playing=false;document.getElementById("play").textContent="play";return;}requestAnimationFrame(frame);}
const m=/tick=(\d+)/.exec(location.hash);
if(m){setPos(+m[1]);}else{setPos(0);playing=true;document.getElementById("play").textContent="pause";requestAnimationFrame(frame);}
window.addEventListener("hashchange",()=>{const m=/tick=(\d+)/.exec(location.hash);if(m){playing=false;setPos(+m[1]);}});
})();
</script>
</body></html>
"##;
