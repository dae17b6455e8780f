"use strict";
// `wbi bridge` as Foxglove sees it: Foxglove's own WebSocket client
// (@foxglove/ws-protocol over `ws`) and its OMG-IDL/CDR decoder
// (@foxglove/omgidl-parser, @foxglove/omgidl-serialization), given only what
// the bridge advertises, against the running demo (deploy/demo.yaml):
//   a. serverInfo and the advertised channels (the DDS streams in CDR with
//      their IDL text; the bridge's own foxglove.FrameTransforms in JSON);
//   b. sensor samples paired with the ground truth of the same stamp: every
//      encoder within half a count of the true joint position;
//   c. one frame transform per URDF link, unit quaternions, ~30 Hz;
//   d. the controller's parameters: listed, set, refused out of range, and a
//      new target reached by the arm (seen in the sensor stream);
//   e. a second client that stops reading does not slow the first one down.
// Prints "ok: ..." per check; exits 0 when all pass, else "FAIL: reason", 1.
//   node foxglove_client_check.js ws://127.0.0.1:PORT path/to/arm7.urdf
const fs = require("fs");
const { performance } = require("perf_hooks");
const WebSocket = require("ws");
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");

const STEP_TIMEOUT_MS = 20000;
const OVERALL_TIMEOUT_MS = 110000;  // inside the C++ driver's 120 s
const SENSORS = "wbi/arm/sensors";
const GROUND_TRUTH = "wbi/arm/ground_truth";
const STATE = "wbi/arm/state";
const TRANSFORMS = "wbi/arm/transforms";
const CDR_TYPES = new Map([
  [SENSORS, "wbi::msg::SensorSample"],
  [GROUND_TRUTH, "wbi::msg::GroundTruth"],
  [STATE, "wbi::msg::StateEstimate"],
]);
const ALL_TOPICS = [...CDR_TYPES.keys(), TRANSFORMS];
// deploy/robots/arm.yaml: 16384 counts per revolution, no position noise, so
// an encoder reading is the true position rounded to the nearest count.
const ENCODER_STEP = (2 * Math.PI) / 16384;  // rad per count
const ENCODER_TOLERANCE = 0.5 * ENCODER_STEP + 1e-12;
const PAIRS_REQUIRED = 1000;
const GAIN_SCALE = "/arm/pd_gravity/gain_scale";
const TARGET = "/arm/pd_gravity/target";
const ROBOT_DESCRIPTION = "/robot_description";
const NEW_TARGET = [0.0, 0.3, 0.0, 0.8, 0.0, 0.5, 0.0];
const TARGET_TOLERANCE = 0.05;  // rad
const SLOW_CLIENT_MIN_RATIO = 0.8;

class CheckFailure extends Error {}

function fail(reason) {
  throw new CheckFailure(reason);
}

function ok(text) {
  console.log(`ok: ${text}`);
}

// From an event callback, where a throw would not reach main(): end the run.
function abort(reason) {
  console.log(`FAIL: ${reason}`);
  process.exit(1);
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Polls until condition() gives a truthy value and returns it; fails after
// timeoutMs, naming `what` (a string, or a function for a message that says
// what was seen instead).
async function waitFor(what, condition, timeoutMs = STEP_TIMEOUT_MS) {
  const deadline = performance.now() + timeoutMs;
  for (;;) {
    const value = condition();
    if (value) {
      return value;
    }
    if (performance.now() > deadline) {
      const text = typeof what === "function" ? what() : what;
      fail(`no ${text} within ${timeoutMs / 1000} s`);
    }
    await sleep(5);
  }
}

// One connection through FoxgloveClient: what the server has said so far, and
// per subscription id the function that takes its payloads.
class Session {
  // tolerateClose: a server may drop a client that stops reading.
  constructor(url, name, { tolerateClose = false } = {}) {
    this.name = name;
    this.socket = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
    this.client = new FoxgloveClient({ ws: this.socket });
    this.serverInfo = undefined;
    this.channels = new Map();  // topic → advertised channel
    this.handlers = new Map();  // subscription id → (payload: Uint8Array) => void
    this.statuses = [];
    this.parameterReplies = [];
    this.closed = false;
    this.finished = false;
    this.client.on("serverInfo", (info) => this.onServerInfo(info));
    this.client.on("advertise", (channels) => channels.forEach((c) => this.channels.set(c.topic, c)));
    this.client.on("unadvertise", (ids) => this.onUnadvertise(ids));
    this.client.on("status", (status) => this.onStatus(status));
    this.client.on("parameterValues", (reply) => this.parameterReplies.push(reply));
    this.client.on("message", (message) => this.onMessage(message));
    this.client.on("error", (error) => abort(`${name}: ${error.message || error}`));
    this.client.on("close", (event) => {
      this.closed = true;
      if (!tolerateClose && !this.finished) {
        abort(`${name}: the server closed the connection (code ${event.code} ${event.reason || ""})`);
      }
    });
  }

  onServerInfo(info) {
    if (this.serverInfo !== undefined) {
      abort(`${this.name}: a second serverInfo`);
    }
    this.serverInfo = info;
  }

  // Kept for the checks, and shown: a status explains many failures.
  onStatus(status) {
    this.statuses.push(status);
    console.log(`note: ${this.name}: status level ${status.level}: ${status.message}`);
  }

  onUnadvertise(ids) {
    for (const [topic, channel] of this.channels) {
      if (ids.includes(channel.id)) {
        this.channels.delete(topic);
      }
    }
  }

  onMessage(message) {
    const handler = this.handlers.get(message.subscriptionId);
    if (handler === undefined) {
      abort(`${this.name}: message data for subscription ${message.subscriptionId}, never requested`);
    }
    const { buffer, byteOffset, byteLength } = message.data;
    handler(new Uint8Array(buffer, byteOffset, byteLength));
  }

  subscribe(topic, handler) {
    const channel = this.channels.get(topic);
    if (channel === undefined) {
      fail(`${this.name}: ${topic} is not advertised`);
    }
    this.handlers.set(this.client.subscribe(channel.id), handler);
  }

  async parameterReply(id) {
    return waitFor(`parameterValues reply with id "${id}"`, () =>
      this.parameterReplies.find((reply) => reply.id === id));
  }

  close() {
    this.finished = true;
    this.socket.terminate();
  }
}

// Every decoded sample of one CDR channel: the latest, how many, and a
// listener a step may set for its own use.
class Feed {
  constructor(session, topic, reader) {
    this.topic = topic;
    this.count = 0;
    this.latest = undefined;
    this.listener = undefined;
    session.subscribe(topic, (payload) => this.take(reader, payload));
  }

  take(reader, payload) {
    let sample;
    try {
      sample = reader.readMessage(payload);
    } catch (error) {
      abort(`${this.topic}: message ${this.count} does not decode: ${error.message}`);
    }
    this.latest = sample;
    ++this.count;
    if (this.listener) {
      this.listener(sample);
    }
  }

  // Samples per second over the next `ms` milliseconds.
  async rate(ms) {
    const count = this.count;
    const start = performance.now();
    await sleep(ms);
    return (this.count - count) / ((performance.now() - start) / 1000);
  }
}

// Link names and root links of a URDF, by regex: enough for the project's
// generated models (comments removed first, they mention tags).
function readUrdf(text) {
  const xml = text.replace(/<!--[\s\S]*?-->/g, "");
  const links = [...xml.matchAll(/<link\s+name\s*=\s*"([^"]+)"/g)].map((m) => m[1]);
  const children = new Set([...xml.matchAll(/<child\s+link\s*=\s*"([^"]+)"/g)].map((m) => m[1]));
  return { links, roots: links.filter((link) => !children.has(link)) };
}

function expectFields(what, object, expected) {
  for (const [key, value] of Object.entries(expected)) {
    if (object[key] !== value) {
      fail(`${what}: ${key} is ${JSON.stringify(object[key])}, expected ${JSON.stringify(value)}`);
    }
  }
}

// a. ------------------------------------------------------------------------

// The channel's own IDL text must define its schemaName: the reader built
// from it is the only decoder of its messages.
function readerOfCdrChannel(channel, type) {
  expectFields(channel.topic, channel, { encoding: "cdr", schemaEncoding: "omgidl", schemaName: type });
  if (typeof channel.schema !== "string" || channel.schema.length === 0) {
    fail(`${channel.topic}: no IDL text in schema`);
  }
  try {
    return new MessageReader(type, parseIDL(channel.schema));
  } catch (error) {
    fail(`${channel.topic}: its schema does not give a reader of ${type}: ${error.message}`);
  }
}

function checkTransformsChannel(channel) {
  expectFields(channel.topic, channel, {
    encoding: "json",
    schemaEncoding: "jsonschema",
    schemaName: "foxglove.FrameTransforms",
  });
  let schema;
  try {
    schema = JSON.parse(channel.schema);
  } catch (error) {
    fail(`${channel.topic}: schema is not JSON: ${error.message}`);
  }
  if (schema === null || typeof schema !== "object" || !schema.properties?.transforms) {
    fail(`${channel.topic}: the JSON schema has no "transforms" property`);
  }
}

async function checkAdvertisements(session) {
  const info = await waitFor("serverInfo", () => session.serverInfo);
  if (session.socket.protocol !== FoxgloveClient.SUPPORTED_SUBPROTOCOL) {
    fail(`subprotocol "${session.socket.protocol}", expected ${FoxgloveClient.SUPPORTED_SUBPROTOCOL}`);
  }
  if (typeof info.name !== "string" || !Array.isArray(info.capabilities)) {
    fail(`serverInfo without name or capabilities: ${JSON.stringify(info)}`);
  }
  ok(`serverInfo "${info.name}", capabilities [${info.capabilities.join(", ")}], subprotocol ${session.socket.protocol}`);

  await waitFor(
    () => `advertisement of ${ALL_TOPICS.filter((t) => !session.channels.has(t)).join(", ")} ` +
      `(advertised: ${[...session.channels.keys()].join(", ") || "none"})`,
    () => ALL_TOPICS.every((topic) => session.channels.has(topic)));
  const ids = [...session.channels.values()].map((channel) => channel.id);
  if (new Set(ids).size !== ids.length) {
    fail(`channel ids are not unique: ${ids.join(", ")}`);
  }
  const readers = new Map();
  for (const [topic, type] of CDR_TYPES) {
    readers.set(topic, readerOfCdrChannel(session.channels.get(topic), type));
  }
  ok(`${[...CDR_TYPES.keys()].join(", ")}: cdr, omgidl, ${[...CDR_TYPES.values()].join(", ")}; ` +
    "their IDL text parses and defines the type");
  checkTransformsChannel(session.channels.get(TRANSFORMS));
  ok(`${TRANSFORMS}: json, jsonschema, foxglove.FrameTransforms (${session.channels.size} channels advertised)`);
  return readers;
}

// b. ------------------------------------------------------------------------

// Pairs sensor samples and ground truth by header.stamp_ns, whichever comes
// first, and keeps the largest |encoder − q|.
class StampPairing {
  constructor() {
    this.encoders = new Map();  // stamp → encoder_position
    this.truths = new Map();    // stamp → q
    this.pairs = 0;
    this.maxError = 0;
    this.worst = "";
    this.seqGaps = 0;
    this.lastSeq = undefined;
  }

  addSensors(sample) {
    if (sample.header.robot !== "arm") {
      abort(`${SENSORS}: header.robot "${sample.header.robot}"`);
    }
    if (this.lastSeq !== undefined && sample.header.seq !== this.lastSeq + 1n) {
      ++this.seqGaps;
    }
    this.lastSeq = sample.header.seq;
    this.encoders.set(sample.header.stamp_ns, sample.encoder_position);
    this.match(sample.header.stamp_ns);
  }

  addTruth(sample) {
    this.truths.set(sample.header.stamp_ns, sample.q);
    this.match(sample.header.stamp_ns);
  }

  match(stamp) {
    const encoders = this.encoders.get(stamp);
    const q = this.truths.get(stamp);
    if (encoders === undefined || q === undefined) {
      return;
    }
    this.encoders.delete(stamp);
    this.truths.delete(stamp);
    if (encoders.length !== q.length || q.length === 0) {
      abort(`stamp ${stamp}: ${encoders.length} encoders, ${q.length} ground-truth joints`);
    }
    for (let j = 0; j < q.length; ++j) {
      const error = Math.abs(encoders[j] - q[j]);
      if (!(error <= this.maxError)) {  // NaN is kept too
        this.maxError = error;
        this.worst = `stamp ${stamp} joint ${j}: encoder ${encoders[j]}, q ${q[j]}`;
      }
    }
    ++this.pairs;
  }
}

async function checkEncodersAgainstGroundTruth(sensors, truth, state) {
  const pairing = new StampPairing();
  sensors.listener = (sample) => pairing.addSensors(sample);
  truth.listener = (sample) => pairing.addTruth(sample);
  await waitFor(() => `${PAIRS_REQUIRED} sensor samples paired with ground truth (${pairing.pairs} paired, ` +
      `${sensors.count} sensor samples and ${truth.count} ground truths received)`,
    () => pairing.pairs >= PAIRS_REQUIRED);
  sensors.listener = undefined;
  truth.listener = undefined;
  if (!(pairing.maxError <= ENCODER_TOLERANCE)) {
    fail(`encoder error ${pairing.maxError} rad > half a count (${ENCODER_TOLERANCE}): ${pairing.worst}`);
  }
  ok(`${pairing.pairs} sensor samples paired with ground truth by stamp; max |encoder − q| = ` +
    `${pairing.maxError.toExponential(3)} rad = ${(pairing.maxError / ENCODER_STEP).toFixed(3)} ` +
    `counts (≤ 0.5); sensor seq gaps ${pairing.seqGaps}; unpaired: ${pairing.encoders.size} sensor, ` +
    `${pairing.truths.size} ground truth`);
  await waitFor(`${STATE} message`, () => state.count > 0);
  ok(`${STATE}: ${state.count} state estimates decoded`);
}

// c. ------------------------------------------------------------------------

function isFiniteNumbers(object, keys) {
  return object !== null && typeof object === "object" && keys.every((key) => Number.isFinite(object[key]));
}

// One foxglove.FrameTransforms message: well formed, unit quaternions, every
// URDF link in the tree, each child frame once. Returns its transform count.
function checkFrameTransforms(message, urdf) {
  if (!Array.isArray(message.transforms)) {
    fail(`${TRANSFORMS}: no transforms array in ${JSON.stringify(message).slice(0, 200)}`);
  }
  const children = new Set();
  const named = new Set();
  for (const t of message.transforms) {
    const what = `${TRANSFORMS}: transform ${JSON.stringify(t)}`;
    const stamp = t.timestamp;
    if (!isFiniteNumbers(stamp, ["sec", "nsec"]) || !Number.isInteger(stamp.sec) ||
        !Number.isInteger(stamp.nsec) || stamp.sec < 0 || stamp.nsec < 0 || stamp.nsec >= 1e9) {
      fail(`${what}: bad timestamp`);
    }
    if (typeof t.parent_frame_id !== "string" || typeof t.child_frame_id !== "string") {
      fail(`${what}: frame ids are not strings`);
    }
    if (!isFiniteNumbers(t.translation, ["x", "y", "z"]) || !isFiniteNumbers(t.rotation, ["x", "y", "z", "w"])) {
      fail(`${what}: translation or rotation missing or not finite`);
    }
    const r = t.rotation;
    const norm = Math.hypot(r.x, r.y, r.z, r.w);
    if (Math.abs(norm - 1) > 1e-6) {
      fail(`${what}: |rotation| = ${norm}`);
    }
    if (!urdf.links.includes(t.child_frame_id) || !urdf.links.includes(t.parent_frame_id)) {
      fail(`${what}: a frame that is no link of the URDF`);
    }
    if (children.has(t.child_frame_id)) {
      fail(`${TRANSFORMS}: two transforms to ${t.child_frame_id}`);
    }
    children.add(t.child_frame_id);
    named.add(t.child_frame_id).add(t.parent_frame_id);
  }
  const missing = urdf.links.filter((link) => !named.has(link) || (!children.has(link) && !urdf.roots.includes(link)));
  if (missing.length > 0) {
    fail(`${TRANSFORMS}: no transform to ${missing.join(", ")}`);
  }
  return message.transforms.length;
}

async function checkTransforms(session, urdf) {
  const arrivals = [];
  let transforms = 0;
  session.subscribe(TRANSFORMS, (payload) => {
    let message;
    try {
      message = JSON.parse(new TextDecoder().decode(payload));
    } catch (error) {
      abort(`${TRANSFORMS}: message ${arrivals.length} is not JSON: ${error.message}`);
    }
    try {
      transforms = checkFrameTransforms(message, urdf);
    } catch (error) {
      abort(error.message);
    }
    arrivals.push(performance.now());
  });
  await waitFor(`${TRANSFORMS} message`, () => arrivals.length > 0);
  const first = arrivals.length;
  await sleep(2000);
  const window = arrivals.slice(first - 1);
  const rate = (window.length - 1) / ((window[window.length - 1] - window[0]) / 1000);
  if (!(window.length >= 5 && rate >= 10 && rate <= 100)) {
    fail(`${TRANSFORMS}: ${window.length} messages in 2 s (${rate.toFixed(1)} Hz), expected ~30 Hz`);
  }
  ok(`${TRANSFORMS}: ${arrivals.length} messages at ${rate.toFixed(1)} Hz, ${transforms} transforms each for ` +
    `the ${urdf.links.length} links of the URDF (root ${urdf.roots.join(", ")}), unit quaternions`);
}

// d. ------------------------------------------------------------------------

function parameterNamed(reply, name) {
  return reply.parameters.find((parameter) => parameter.name === name);
}

function expectParameter(reply, name, check, what) {
  const parameter = parameterNamed(reply, name);
  if (parameter === undefined) {
    fail(`parameterValues "${reply.id}" has no ${name} (has ${reply.parameters.map((p) => p.name).join(", ")})`);
  }
  if (!check(parameter)) {
    fail(`${name} = ${JSON.stringify(parameter).slice(0, 300)}, expected ${what}`);
  }
  return parameter;
}

const isFloat64 = (value) => (p) => p.type === "float64" && p.value === value;
const isArrayOf = (n) => (p) => p.type === "float64_array" && Array.isArray(p.value) &&
  p.value.length === n && p.value.every(Number.isFinite);
const sameArray = (expected) => (p) => isArrayOf(expected.length)(p) &&
  p.value.every((v, i) => v === expected[i]);

function maxTargetError(sample) {
  return Math.max(...NEW_TARGET.map((q, j) => Math.abs(sample.encoder_position[j] - q)));
}

async function checkListing(session, urdf) {
  session.client.getParameters([], "list-all");
  const all = await session.parameterReply("list-all");
  expectParameter(all, GAIN_SCALE, (p) => p.type === "float64" && Number.isFinite(p.value), "a float64");
  expectParameter(all, TARGET, isArrayOf(7), "a float64_array of 7 values");
  expectParameter(all, ROBOT_DESCRIPTION, (p) => typeof p.value === "string" &&
    JSON.stringify(readUrdf(p.value).links) === JSON.stringify(urdf.links), "the URDF text, the same links");
  ok(`getParameters lists ${all.parameters.length} parameters, among them ${GAIN_SCALE} = ` +
    `${parameterNamed(all, GAIN_SCALE).value}, ${TARGET} = [${parameterNamed(all, TARGET).value.join(", ")}], ` +
    `${ROBOT_DESCRIPTION} (${parameterNamed(all, ROBOT_DESCRIPTION).value.length} characters of URDF)`);
}

async function checkNewTarget(session, sensors) {
  session.client.setParameters([{ name: TARGET, value: NEW_TARGET, type: "float64_array" }], "set-target");
  expectParameter(await session.parameterReply("set-target"), TARGET, sameArray(NEW_TARGET), `[${NEW_TARGET}]`);
  const start = performance.now();
  const initial = maxTargetError(sensors.latest);
  await waitFor(() => `encoders within ${TARGET_TOLERANCE} rad of the new target (max error now ` +
      `${maxTargetError(sensors.latest).toFixed(4)} rad)`,
    () => maxTargetError(sensors.latest) < TARGET_TOLERANCE, 15000);
  ok(`${TARGET} set to [${NEW_TARGET.join(", ")}]: the encoders came from ${initial.toFixed(3)} rad to within ` +
    `${TARGET_TOLERANCE} rad in ${((performance.now() - start) / 1000).toFixed(2)} s`);
}

async function checkOutOfRange(session) {
  const statusesBefore = session.statuses.length;
  session.client.setParameters([{ name: GAIN_SCALE, value: 100, type: "float64" }], "set-out-of-range");
  const status = await waitFor(`status of level 2 naming ${GAIN_SCALE}`, () =>
    session.statuses.slice(statusesBefore).find((s) => s.level === 2 && s.message.includes(GAIN_SCALE)));
  session.client.getParameters([GAIN_SCALE], "after-out-of-range");
  expectParameter(await session.parameterReply("after-out-of-range"), GAIN_SCALE, isFloat64(0.5), "still 0.5");
  const reply = session.parameterReplies.find((r) => r.id === "set-out-of-range");
  if (reply !== undefined && parameterNamed(reply, GAIN_SCALE)?.value === 100) {
    fail(`the refused set was answered with ${GAIN_SCALE} = 100`);
  }
  ok(`${GAIN_SCALE} = 100 refused: status level 2 "${status.message}"; the value stays 0.5`);
}

async function checkParameters(session, sensors, urdf) {
  if (!session.serverInfo.capabilities.includes("parameters")) {
    fail(`serverInfo capabilities [${session.serverInfo.capabilities}] lack "parameters"`);
  }
  await checkListing(session, urdf);
  session.client.setParameters([{ name: GAIN_SCALE, value: 0.5, type: "float64" }], "set-gain");
  expectParameter(await session.parameterReply("set-gain"), GAIN_SCALE, isFloat64(0.5), "0.5 (float64)");
  ok(`setParameters ${GAIN_SCALE} = 0.5: the reply with id "set-gain" shows 0.5`);
  await checkNewTarget(session, sensors);
  await checkOutOfRange(session);
}

// e. ------------------------------------------------------------------------

// A client that subscribes to everything and then leaves its socket unread,
// so that the server's TCP send buffer to it fills.
async function startStalledClient(url) {
  const slow = new Session(url, "stalled client", { tolerateClose: true });
  await waitFor("serverInfo on the second connection", () => slow.serverInfo);
  await waitFor("the advertisements on the second connection",
    () => ALL_TOPICS.every((topic) => slow.channels.has(topic)));
  let received = 0;
  for (const topic of slow.channels.keys()) {
    slow.subscribe(topic, () => ++received);
  }
  await waitFor("a message on the second connection", () => received > 0);
  slow.socket.pause();
  return { slow, received: () => received };
}

async function checkStalledClient(url, sensors) {
  const before = await sensors.rate(2000);
  const { slow, received } = await startStalledClient(url);
  const readBeforePause = received();
  const during = await sensors.rate(3000);
  const ratio = during / before;
  const dropped = slow.closed ? "; the server closed it" : "";
  slow.close();
  if (!(ratio >= SLOW_CLIENT_MIN_RATIO)) {
    fail(`with a stalled second client ${SENSORS} came at ${during.toFixed(0)} Hz, ` +
      `${(100 * ratio).toFixed(0)} % of the ${before.toFixed(0)} Hz before`);
  }
  ok(`${SENSORS} at ${before.toFixed(0)} Hz before and ${during.toFixed(0)} Hz (${(100 * ratio).toFixed(0)} %) ` +
    `during 3 s with a second client subscribed to ${slow.channels.size} channels that stopped reading ` +
    `(after ${readBeforePause} messages${dropped})`);
}

// ---------------------------------------------------------------------------

async function main(url, urdfPath) {
  const urdf = readUrdf(fs.readFileSync(urdfPath, "utf8"));
  if (urdf.links.length === 0) {
    fail(`${urdfPath}: no links`);
  }
  const session = new Session(url, "first client");
  const readers = await checkAdvertisements(session);
  const sensors = new Feed(session, SENSORS, readers.get(SENSORS));
  const truth = new Feed(session, GROUND_TRUTH, readers.get(GROUND_TRUTH));
  const state = new Feed(session, STATE, readers.get(STATE));
  await checkEncodersAgainstGroundTruth(sensors, truth, state);
  await checkTransforms(session, urdf);
  await checkParameters(session, sensors, urdf);
  await checkStalledClient(url, sensors);
  session.close();
}

if (process.argv.length !== 4) {
  console.log("usage: node foxglove_client_check.js ws://HOST:PORT path/to/arm7.urdf");
  process.exit(2);
}
setTimeout(() => abort(`not done within ${OVERALL_TIMEOUT_MS / 1000} s`), OVERALL_TIMEOUT_MS).unref();
main(process.argv[2], process.argv[3]).then(
  () => process.exit(0),
  (error) => abort(error instanceof CheckFailure ? error.message : error.stack || String(error)));
