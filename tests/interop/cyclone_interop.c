/* A client of a running wbi robot written with Eclipse Cyclone DDS only: its
 * types come from the .idl files of idl/ through Cyclone's own idlc, it includes no wbi
 * header and links no Fast DDS. It is the proof that the IDL files are the
 * whole wire contract (idl/README.md, "Speaking wbi from another DDS").
 *
 *   wbi_interop_cyclone --robot arm [--domain N] [--samples 300] [--joint 0 --move 0.2]
 *                       [--gravity-at q1,...,qn] [--timeout 30]
 *
 * Checks, in order (one line each on stdout; a failure prints one line on
 * stderr and exits 1):
 *   description  wbi/<robot>/description (latched) names the joints;
 *   sensors      wbi/<robot>/sensors against wbi/<robot>/ground_truth, paired by
 *                header.seq: every encoder within --position-tolerance of q;
 *   state        wbi/<robot>/state against the ground truth, paired by
 *                header.stamp_ns (the estimate carries its sensor sample's stamp);
 *   command      a POSITION command on wbi/<robot>/commands moves one joint by
 *                --move rad, seen on the sensors;
 *   status       wbi/status of the robot's component (--component, default the
 *                robot name): ACTIVE, the command counted as accepted;
 *   model        with --gravity-at: GRAVITY_FORCES from the model service
 *                (wbi/<robot>/model/request and /reply), printed as
 *                "gravity_forces: g1 ... gn" for the caller to check.
 * The domain id: --domain, else WBI_DOMAIN_ID, else 0. Network settings come
 * from CYCLONEDDS_URI (cyclonedds_loopback.xml meets wbi's loopback-only
 * participants). */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dds/dds.h>
#include <dds/version.h>

#include "commands.h"
#include "description.h"
#include "model.h"
#include "sensors.h"
#include "state.h"
#include "status.h"

enum { kMaxRecords = 8192, kTakeBatch = 64 };

typedef struct {
  const char* robot;
  const char* component;
  int domain;
  int samples;
  double position_tolerance;
  int joint;
  double move;
  double reach_tolerance;
  double timeout_s;
  int gravity_joints;
  double gravity_at[wbi_msg_MAX_JOINTS];
} Options;

/* Joint positions of one sample, with its header. */
typedef struct {
  uint64_t seq;
  int64_t stamp_ns;
  uint32_t n;
  double q[wbi_msg_MAX_JOINTS];
} Record;

typedef struct {
  Record* items;
  size_t count;
} Records;

static void fail(const char* format, ...) {
  va_list args;
  va_start(args, format);
  fputs("wbi_interop_cyclone: ", stderr);
  vfprintf(stderr, format, args);
  fputc('\n', stderr);
  va_end(args);
  exit(1);
}

static void check_dds(dds_return_t rc, const char* what) {
  if (rc < 0) {
    fail("%s: %s", what, dds_strretcode(rc));
  }
}

static dds_time_t deadline_after(double seconds) {
  return dds_time() + (dds_duration_t)(seconds * 1e9);
}

static double parse_number(const char* text, const char* option) {
  char* end = NULL;
  errno = 0;
  const double value = strtod(text, &end);
  if (errno != 0 || end == text || *end != '\0' || !isfinite(value)) {
    fail("%s: '%s' is not a number", option, text);
  }
  return value;
}

static int parse_list(const char* text, double* out, int capacity, const char* option) {
  int count = 0;
  char buffer[4096];
  if (strlen(text) >= sizeof buffer) {
    fail("%s: list too long", option);
  }
  strcpy(buffer, text);
  for (char* item = strtok(buffer, ","); item != NULL; item = strtok(NULL, ",")) {
    if (count == capacity) {
      fail("%s: more than %d values", option, capacity);
    }
    out[count++] = parse_number(item, option);
  }
  return count;
}

static Options parse_options(int argc, char** argv) {
  Options options = {.robot = NULL,
                     .component = NULL,
                     .domain = 0,
                     .samples = 300,
                     /* half an encoder count of the arm (2^14 counts per turn): the
                        sensor model rounds q to the nearest count */
                     .position_tolerance = M_PI / 16384.0 + 1e-9,
                     .joint = 0,
                     .move = 0.2,
                     .reach_tolerance = 0.01,
                     .timeout_s = 30.0,
                     .gravity_joints = 0};
  const char* domain = getenv("WBI_DOMAIN_ID");
  if (domain != NULL && *domain != '\0') {
    options.domain = (int)parse_number(domain, "WBI_DOMAIN_ID");
  }
  for (int i = 1; i < argc; ++i) {
    const char* option = argv[i];
    if (strcmp(option, "--help") == 0 || strcmp(option, "-h") == 0) {
      printf(
          "usage: wbi_interop_cyclone --robot NAME [--component INSTANCE] [--domain N]\n"
          "       [--samples N]\n"
          "       [--position-tolerance RAD] [--joint INDEX] [--move RAD]\n"
          "       [--reach-tolerance RAD] [--gravity-at q1,...,qn] [--timeout S]\n");
      exit(0);
    }
    if (i + 1 >= argc) {
      fail("%s needs a value (see --help)", option);
    }
    const char* value = argv[++i];
    if (strcmp(option, "--robot") == 0) {
      options.robot = value;
    } else if (strcmp(option, "--component") == 0) {
      options.component = value;
    } else if (strcmp(option, "--domain") == 0) {
      options.domain = (int)parse_number(value, option);
    } else if (strcmp(option, "--samples") == 0) {
      options.samples = (int)parse_number(value, option);
    } else if (strcmp(option, "--position-tolerance") == 0) {
      options.position_tolerance = parse_number(value, option);
    } else if (strcmp(option, "--joint") == 0) {
      options.joint = (int)parse_number(value, option);
    } else if (strcmp(option, "--move") == 0) {
      options.move = parse_number(value, option);
    } else if (strcmp(option, "--reach-tolerance") == 0) {
      options.reach_tolerance = parse_number(value, option);
    } else if (strcmp(option, "--timeout") == 0) {
      options.timeout_s = parse_number(value, option);
    } else if (strcmp(option, "--gravity-at") == 0) {
      options.gravity_joints = parse_list(value, options.gravity_at, wbi_msg_MAX_JOINTS, option);
    } else {
      fail("unknown option '%s' (see --help)", option);
    }
  }
  if (options.robot == NULL) {
    fail("--robot NAME is required (see --help)");
  }
  if (options.component == NULL) {
    options.component = options.robot;
  }
  if (options.samples < 1 || options.samples > kMaxRecords / 2) {
    fail("--samples must be in [1, %d]", kMaxRecords / 2);
  }
  return options;
}

/* ---- QoS: what deploy/qos_profiles.xml gives wbi's writers (idl/README.md) ---- */

static dds_qos_t* qos(dds_reliability_kind_t reliability, dds_durability_kind_t durability,
                      int32_t depth) {
  dds_qos_t* q = dds_create_qos();
  dds_qset_reliability(q, reliability, DDS_SECS(1));
  dds_qset_durability(q, durability);
  dds_qset_history(q, DDS_HISTORY_KEEP_LAST, depth);
  return q;
}

static dds_entity_t topic(dds_entity_t participant, const dds_topic_descriptor_t* type,
                          const char* robot, const char* what) {
  char name[256];
  if (robot != NULL) {
    snprintf(name, sizeof name, "wbi/%s/%s", robot, what);
  } else {
    snprintf(name, sizeof name, "%s", what);
  }
  const dds_entity_t t = dds_create_topic(participant, type, name, NULL, NULL);
  check_dds(t, name);
  return t;
}

static dds_entity_t reader(dds_entity_t participant, dds_entity_t t, dds_qos_t* q) {
  const dds_entity_t r = dds_create_reader(participant, t, q, NULL);
  dds_delete_qos(q);
  check_dds(r, "create reader");
  return r;
}

static dds_entity_t writer(dds_entity_t participant, dds_entity_t t, dds_qos_t* q) {
  const dds_entity_t w = dds_create_writer(participant, t, q, NULL);
  dds_delete_qos(q);
  check_dds(w, "create writer");
  return w;
}

/* Waits until `entity` (a reader or a writer) has matched a remote endpoint. */
static void wait_matched(dds_entity_t participant, dds_entity_t entity, bool is_writer,
                         const char* what, dds_time_t deadline) {
  const uint32_t status =
      is_writer ? DDS_PUBLICATION_MATCHED_STATUS : DDS_SUBSCRIPTION_MATCHED_STATUS;
  check_dds(dds_set_status_mask(entity, status), "set status mask");
  const dds_entity_t waitset = dds_create_waitset(participant);
  check_dds(dds_waitset_attach(waitset, entity, entity), "attach");
  for (;;) {
    uint32_t count = 0;
    if (is_writer) {
      dds_publication_matched_status_t matched;
      check_dds(dds_get_publication_matched_status(entity, &matched), "matched status");
      count = matched.current_count;
    } else {
      dds_subscription_matched_status_t matched;
      check_dds(dds_get_subscription_matched_status(entity, &matched), "matched status");
      count = matched.current_count;
    }
    if (count > 0) {
      break;
    }
    if (dds_waitset_wait_until(waitset, NULL, 0, deadline) == 0) {
      fail(
          "%s: no wbi endpoint matched (is the robot running on this domain? "
          "CYCLONEDDS_URI set?)",
          what);
    }
  }
  dds_delete(waitset);
}

/* Waits until a reader of `waitset` (data_waitset) has data; false at the deadline. */
static bool wait_data(dds_entity_t waitset, dds_time_t deadline) {
  return dds_waitset_wait_until(waitset, NULL, 0, deadline) > 0;
}

static dds_entity_t data_waitset(dds_entity_t participant, const dds_entity_t* readers, int count) {
  const dds_entity_t waitset = dds_create_waitset(participant);
  for (int i = 0; i < count; ++i) {
    const dds_entity_t condition = dds_create_readcondition(readers[i], DDS_ANY_STATE);
    check_dds(dds_waitset_attach(waitset, condition, readers[i]), "attach read condition");
  }
  return waitset;
}

static void append(Records* records, const wbi_msg_Header* header, const dds_sequence_double* q) {
  if (records->count == kMaxRecords) {
    return;
  }
  Record* record = &records->items[records->count++];
  record->seq = header->seq;
  record->stamp_ns = header->stamp_ns;
  record->n = q->_length;
  memcpy(record->q, q->_buffer, q->_length * sizeof(double));
}

static void check_robot(const wbi_msg_Header* header, const char* robot, const char* topic_name) {
  if (strcmp(header->robot, robot) != 0) {
    fail("%s: header.robot '%s', expected '%s'", topic_name, header->robot, robot);
  }
}

/* ---- checks ---- */

static uint32_t check_description(dds_entity_t participant, const Options* options,
                                  char joint_names[][wbi_msg_MAX_NAME + 1]) {
  const dds_entity_t t =
      topic(participant, &wbi_msg_RobotDescription_desc, options->robot, "description");
  const dds_entity_t r =
      reader(participant, t, qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_TRANSIENT_LOCAL, 1));
  const dds_entity_t waitset = data_waitset(participant, &r, 1);
  const dds_time_t deadline = deadline_after(options->timeout_s);
  for (;;) {
    void* samples[1] = {NULL};
    dds_sample_info_t infos[1];
    const dds_return_t n = dds_take(r, samples, infos, 1, 1);
    check_dds(n, "take description");
    if (n == 1 && infos[0].valid_data) {
      const wbi_msg_RobotDescription* d = samples[0];
      check_robot(&d->header, options->robot, "description");
      const uint32_t joints = d->joint_names._length;
      if (joints == 0 || d->joint_limits._length != joints) {
        fail("description: %" PRIu32 " joint names and %" PRIu32 " joint limits", joints,
             d->joint_limits._length);
      }
      printf("description: %" PRIu32 " joints (%s ... %s), urdf %s\n", joints,
             d->joint_names._buffer[0], d->joint_names._buffer[joints - 1], d->urdf_path);
      for (uint32_t j = 0; j < joints; ++j) {
        snprintf(joint_names[j], wbi_msg_MAX_NAME + 1, "%s", d->joint_names._buffer[j]);
      }
      dds_return_loan(r, samples, n);
      dds_delete(waitset);
      return joints;
    }
    if (n > 0) {
      dds_return_loan(r, samples, n);
    }
    if (!wait_data(waitset, deadline)) {
      fail(
          "description: nothing on wbi/%s/description within %.0f s (no wbi robot on domain "
          "%d? CYCLONEDDS_URI not cyclonedds_loopback.xml?)",
          options->robot, options->timeout_s, options->domain);
    }
  }
}

/* The sample of `records` with this seq (records are in arrival order, seqs rising). */
static const Record* find_seq(const Records* records, uint64_t seq) {
  size_t low = 0;
  size_t high = records->count;
  while (low < high) {
    const size_t mid = (low + high) / 2;
    if (records->items[mid].seq < seq) {
      low = mid + 1;
    } else {
      high = mid;
    }
  }
  return low < records->count && records->items[low].seq == seq ? &records->items[low] : NULL;
}

static const Record* find_stamp(const Records* records, int64_t stamp_ns) {
  size_t low = 0;
  size_t high = records->count;
  while (low < high) {
    const size_t mid = (low + high) / 2;
    if (records->items[mid].stamp_ns < stamp_ns) {
      low = mid + 1;
    } else {
      high = mid;
    }
  }
  return low < records->count && records->items[low].stamp_ns == stamp_ns ? &records->items[low]
                                                                          : NULL;
}

/* Largest |a - b| over the joints, pairing each record of `samples` with the
 * ground truth of the same seq (by_seq) or stamp; returns the pairs found. */
static size_t compare(const Records* samples, const Records* truth, bool by_seq, uint32_t joints,
                      double* max_difference, const char* what) {
  size_t pairs = 0;
  *max_difference = 0.0;
  for (size_t i = 0; i < samples->count; ++i) {
    const Record* s = &samples->items[i];
    const Record* t = by_seq ? find_seq(truth, s->seq) : find_stamp(truth, s->stamp_ns);
    if (t == NULL) {
      continue;
    }
    if (s->n != joints || t->n != joints) {
      fail("%s: %" PRIu32 " joint values, ground truth %" PRIu32 ", description %" PRIu32, what,
           s->n, t->n, joints);
    }
    for (uint32_t j = 0; j < joints; ++j) {
      const double difference = fabs(s->q[j] - t->q[j]);
      if (!(difference <= *max_difference)) {
        *max_difference = difference; /* NaN propagates to the check */
      }
    }
    ++pairs;
  }
  return pairs;
}

static void check_streams(dds_entity_t participant, const Options* options, uint32_t joints) {
  /* The streams are reliable and transient-local on the writer side (wbi.stream):
     a reliable reader matches; a deep history keeps every sample between takes. */
  const dds_entity_t sensors =
      reader(participant, topic(participant, &wbi_msg_SensorSample_desc, options->robot, "sensors"),
             qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_VOLATILE, 1000));
  const dds_entity_t truth = reader(
      participant, topic(participant, &wbi_msg_GroundTruth_desc, options->robot, "ground_truth"),
      qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_VOLATILE, 1000));
  const dds_entity_t state =
      reader(participant, topic(participant, &wbi_msg_StateEstimate_desc, options->robot, "state"),
             qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_VOLATILE, 1000));
  const dds_entity_t readers[3] = {sensors, truth, state};
  const dds_entity_t waitset = data_waitset(participant, readers, 3);

  Records sensor_records = {calloc(kMaxRecords, sizeof(Record)), 0};
  Records truth_records = {calloc(kMaxRecords, sizeof(Record)), 0};
  Records state_records = {calloc(kMaxRecords, sizeof(Record)), 0};
  if (sensor_records.items == NULL || truth_records.items == NULL || state_records.items == NULL) {
    fail("out of memory");
  }
  const size_t wanted = (size_t)options->samples;
  const dds_time_t deadline = deadline_after(options->timeout_s);
  /* Until enough sensor and state samples came and the ground truth has caught
     up with both (it may arrive after them). */
  for (;;) {
    void* samples[kTakeBatch] = {NULL};
    dds_sample_info_t infos[kTakeBatch];
    dds_return_t n = dds_take(sensors, samples, infos, kTakeBatch, kTakeBatch);
    check_dds(n, "take sensors");
    for (int i = 0; i < n; ++i) {
      if (infos[i].valid_data) {
        const wbi_msg_SensorSample* s = samples[i];
        check_robot(&s->header, options->robot, "sensors");
        append(&sensor_records, &s->header, &s->encoder_position);
      }
    }
    if (n > 0) {
      dds_return_loan(sensors, samples, n);
    }
    n = dds_take(truth, samples, infos, kTakeBatch, kTakeBatch);
    check_dds(n, "take ground truth");
    for (int i = 0; i < n; ++i) {
      if (infos[i].valid_data) {
        const wbi_msg_GroundTruth* g = samples[i];
        check_robot(&g->header, options->robot, "ground_truth");
        append(&truth_records, &g->header, &g->q);
      }
    }
    if (n > 0) {
      dds_return_loan(truth, samples, n);
    }
    n = dds_take(state, samples, infos, kTakeBatch, kTakeBatch);
    check_dds(n, "take state");
    for (int i = 0; i < n; ++i) {
      if (infos[i].valid_data) {
        const wbi_msg_StateEstimate* e = samples[i];
        check_robot(&e->header, options->robot, "state");
        append(&state_records, &e->header, &e->q);
      }
    }
    if (n > 0) {
      dds_return_loan(state, samples, n);
    }
    const bool enough = sensor_records.count >= wanted && state_records.count >= wanted;
    const bool caught_up =
        truth_records.count > 0 &&
        truth_records.items[truth_records.count - 1].seq >=
            sensor_records.items[sensor_records.count > 0 ? sensor_records.count - 1 : 0].seq &&
        truth_records.items[truth_records.count - 1].stamp_ns >=
            state_records.items[state_records.count > 0 ? state_records.count - 1 : 0].stamp_ns;
    if ((enough && caught_up) || truth_records.count == kMaxRecords ||
        sensor_records.count == kMaxRecords || state_records.count == kMaxRecords) {
      break;
    }
    if (!wait_data(waitset, deadline)) {
      fail("streams: within %.0f s: %zu sensor, %zu state, %zu ground-truth samples (%zu wanted)",
           options->timeout_s, sensor_records.count, state_records.count, truth_records.count,
           wanted);
    }
  }

  double sensor_max = 0.0;
  const size_t sensor_pairs =
      compare(&sensor_records, &truth_records, true, joints, &sensor_max, "sensors");
  double state_max = 0.0;
  const size_t state_pairs =
      compare(&state_records, &truth_records, false, joints, &state_max, "state");
  printf(
      "sensors: %zu samples paired with the ground truth by seq (of %zu), max |encoder - q| = %.3g "
      "rad\n",
      sensor_pairs, sensor_records.count, sensor_max);
  printf(
      "state: %zu samples paired with the ground truth by stamp (of %zu), max |q_est - q| = %.3g "
      "rad\n",
      state_pairs, state_records.count, state_max);
  if (sensor_pairs < wanted / 2 || state_pairs < wanted / 2) {
    fail("streams: too few pairs (%zu sensor, %zu state; at least %zu wanted)", sensor_pairs,
         state_pairs, wanted / 2);
  }
  if (!(sensor_max <= options->position_tolerance) || !(state_max <= options->position_tolerance)) {
    fail("streams: a joint position differs from the ground truth by more than %.3g rad",
         options->position_tolerance);
  }
  free(sensor_records.items);
  free(truth_records.items);
  free(state_records.items);
  dds_delete(waitset);
  dds_delete(sensors);
  dds_delete(truth);
  dds_delete(state);
}

static uint64_t counter(const wbi_msg_ComponentStatus* s, const char* name) {
  for (uint32_t i = 0; i < s->counters._length; ++i) {
    if (strcmp(s->counters._buffer[i].name, name) == 0) {
      return s->counters._buffer[i].value;
    }
  }
  return UINT64_MAX;
}

/* After the command: the robot's component reports it ACTIVE, with the
   command counted as accepted and none rejected. */
static void check_status(dds_entity_t participant, const Options* options) {
  /* wbi.status is best effort: a reliable reader would not match. */
  const dds_entity_t r =
      reader(participant, topic(participant, &wbi_msg_ComponentStatus_desc, NULL, "wbi/status"),
             qos(DDS_RELIABILITY_BEST_EFFORT, DDS_DURABILITY_VOLATILE, 16));
  const dds_entity_t waitset = data_waitset(participant, &r, 1);
  const dds_time_t deadline = deadline_after(options->timeout_s);
  for (;;) {
    void* samples[kTakeBatch] = {NULL};
    dds_sample_info_t infos[kTakeBatch];
    const dds_return_t n = dds_take(r, samples, infos, kTakeBatch, kTakeBatch);
    check_dds(n, "take status");
    for (int i = 0; i < n; ++i) {
      const wbi_msg_ComponentStatus* s = samples[i];
      if (!infos[i].valid_data || strcmp(s->instance, options->component) != 0) {
        continue;
      }
      const uint64_t accepted = counter(s, "accepted_commands");
      const uint64_t rejected = counter(s, "rejected_commands");
      if (s->state != wbi_msg_ACTIVE || accepted == 0 || accepted == UINT64_MAX) {
        continue; /* an earlier status, from before the command */
      }
      if (rejected != 0) {
        fail("status: '%s' rejected %" PRIu64 " command(s): %s", s->instance, rejected,
             s->last_error);
      }
      printf("status: '%s' (%s) ACTIVE, %u counters, accepted_commands %" PRIu64
             ", rejected_commands %" PRIu64 "\n",
             s->instance, s->type, s->counters._length, accepted, rejected);
      dds_return_loan(r, samples, n);
      dds_delete(waitset);
      dds_delete(r);
      return;
    }
    if (n > 0) {
      dds_return_loan(r, samples, n);
    }
    if (!wait_data(waitset, deadline)) {
      fail(
          "status: no status of '%s' on wbi/status, ACTIVE and counting the command as "
          "accepted, within %.0f s",
          options->component, options->timeout_s);
    }
  }
}

/* Takes sensor samples until `done` says so or the deadline; returns the last position of `joint`.
 */
static double latest_position(dds_entity_t r, dds_entity_t waitset, uint32_t joint,
                              dds_time_t deadline, double target, double tolerance, bool* reached) {
  double position = NAN;
  *reached = false;
  for (;;) {
    void* samples[kTakeBatch] = {NULL};
    dds_sample_info_t infos[kTakeBatch];
    const dds_return_t n = dds_take(r, samples, infos, kTakeBatch, kTakeBatch);
    check_dds(n, "take sensors");
    for (int i = 0; i < n; ++i) {
      const wbi_msg_SensorSample* s = samples[i];
      if (infos[i].valid_data && joint < s->encoder_position._length) {
        position = s->encoder_position._buffer[joint];
      }
    }
    if (n > 0) {
      dds_return_loan(r, samples, n);
    }
    if (!isnan(position) && (isnan(target) || fabs(position - target) <= tolerance)) {
      *reached = true;
      return position;
    }
    if (!wait_data(waitset, deadline)) {
      return position;
    }
  }
}

static void check_command(dds_entity_t participant, const Options* options, uint32_t joints,
                          char joint_names[][wbi_msg_MAX_NAME + 1]) {
  if (options->joint < 0 || (uint32_t)options->joint >= joints) {
    fail("--joint %d: the robot has %" PRIu32 " joints", options->joint, joints);
  }
  const uint32_t joint = (uint32_t)options->joint;
  const dds_entity_t sensors =
      reader(participant, topic(participant, &wbi_msg_SensorSample_desc, options->robot, "sensors"),
             qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_TRANSIENT_LOCAL, 1));
  const dds_entity_t waitset = data_waitset(participant, &sensors, 1);
  /* wbi.command: reliable and volatile; the robot's reader is reliable, so a
     best-effort writer would not match it. */
  const dds_entity_t commands = writer(
      participant, topic(participant, &wbi_msg_ActuatorCommand_desc, options->robot, "commands"),
      qos(DDS_RELIABILITY_RELIABLE, DDS_DURABILITY_VOLATILE, 8));
  dds_time_t deadline = deadline_after(options->timeout_s);
  wait_matched(participant, commands, true, "commands", deadline);

  bool reached = false;
  const double start = latest_position(sensors, waitset, joint, deadline, NAN, 0.0, &reached);
  if (!reached) {
    fail("command: no sensor sample within %.0f s", options->timeout_s);
  }
  const double target = start + options->move;

  uint16_t joint_index = (uint16_t)joint;
  wbi_msg_ControlMode mode = wbi_msg_POSITION;
  double reference = target;
  wbi_msg_ActuatorCommand command;
  memset(&command, 0, sizeof command);
  snprintf(command.header.robot, sizeof command.header.robot, "%s", options->robot);
  command.header.stamp_ns = dds_time();
  command.header.seq = 0;
  snprintf(command.controller, sizeof command.controller, "cyclone_interop");
  command.joints = (dds_sequence_unsigned_short){1, 1, &joint_index, false};
  command.modes = (dds_sequence_wbi_msg_ControlMode){1, 1, &mode, false};
  command.references = (dds_sequence_double){1, 1, &reference, false};
  const dds_time_t sent = dds_time();
  check_dds(dds_write(commands, &command), "write command");

  deadline = deadline_after(options->timeout_s);
  const double last = latest_position(sensors, waitset, joint, deadline, target,
                                      options->reach_tolerance, &reached);
  if (!reached) {
    fail("command: %s POSITION %.4f rad not reached within %.0f s (at %.4f, from %.4f)",
         joint_names[joint], target, options->timeout_s, last, start);
  }
  printf("command: %s POSITION %+.3f rad (%.4f -> %.4f) reached within %.1f mrad after %.2f s\n",
         joint_names[joint], options->move, start, target, options->reach_tolerance * 1e3,
         (double)(dds_time() - sent) * 1e-9);
  dds_delete(waitset);
  dds_delete(commands);
  dds_delete(sensors);
}

/* The request/reply mapping of wbi (dds/include/wbi/dds/rpc.hpp): two plain
   topics; client_id + seq in the request, echoed in the reply. client_id is the
   GUID of the client's reply reader in 32 hex digits, which lets the server
   hold a request until its reply writer has matched that reader. */
static void guid_hex(const dds_guid_t* guid, char* text) {
  static const char digits[] = "0123456789abcdef";
  for (int i = 0; i < 16; ++i) {
    text[2 * i] = digits[guid->v[i] >> 4];
    text[2 * i + 1] = digits[guid->v[i] & 0xF];
  }
  text[32] = '\0';
}

static void check_model(dds_entity_t participant, const Options* options) {
  /* wbi.request_reply: best effort, volatile; the client resends. */
  const dds_entity_t requests = writer(
      participant, topic(participant, &wbi_msg_ModelRequest_desc, options->robot, "model/request"),
      qos(DDS_RELIABILITY_BEST_EFFORT, DDS_DURABILITY_VOLATILE, 64));
  const dds_entity_t replies = reader(
      participant, topic(participant, &wbi_msg_ModelReply_desc, options->robot, "model/reply"),
      qos(DDS_RELIABILITY_BEST_EFFORT, DDS_DURABILITY_VOLATILE, 64));
  const dds_time_t deadline = deadline_after(options->timeout_s);
  wait_matched(participant, requests, true, "model request", deadline);
  wait_matched(participant, replies, false, "model reply", deadline);

  dds_guid_t guid;
  check_dds(dds_get_guid(replies, &guid), "reply reader guid");
  wbi_msg_ModelRequest request;
  memset(&request, 0, sizeof request);
  guid_hex(&guid, request.client_id);
  request.seq = 1;
  snprintf(request.robot, sizeof request.robot, "%s", options->robot);
  request.state.base_pose.orientation.w = 1.0;
  double zeros[wbi_msg_MAX_JOINTS] = {0};
  const uint32_t n = (uint32_t)options->gravity_joints;
  request.state.q = (dds_sequence_double){n, n, (double*)options->gravity_at, false};
  request.state.dq = (dds_sequence_double){n, n, zeros, false};
  request.state.gravity = (wbi_msg_Vector3){0.0, 0.0, -9.81};
  wbi_msg_OperationRequest operation = {.operation = wbi_msg_GRAVITY_FORCES};
  request.operations = (dds_sequence_wbi_msg_OperationRequest){1, 1, &operation, false};

  const dds_entity_t waitset = data_waitset(participant, &replies, 1);
  const dds_time_t sent = dds_time();
  dds_duration_t resend = DDS_MSECS(2);
  for (;;) {
    check_dds(dds_write(requests, &request), "write model request");
    const dds_time_t resend_at = dds_time() + resend;
    resend = resend * 2 > DDS_MSECS(100) ? DDS_MSECS(100) : resend * 2;
    while (dds_time() < resend_at) {
      void* samples[kTakeBatch] = {NULL};
      dds_sample_info_t infos[kTakeBatch];
      const dds_return_t count = dds_take(replies, samples, infos, kTakeBatch, kTakeBatch);
      check_dds(count, "take model reply");
      for (int i = 0; i < count; ++i) {
        const wbi_msg_ModelReply* reply = samples[i];
        if (!infos[i].valid_data || strcmp(reply->client_id, request.client_id) != 0 ||
            reply->seq != request.seq) {
          continue; /* another client's reply, or a probe's */
        }
        if (reply->error[0] != '\0') {
          fail("model: the service answered with an error: %s", reply->error);
        }
        if (reply->results._length != 1 ||
            reply->results._buffer[0].operation != wbi_msg_GRAVITY_FORCES) {
          fail("model: %" PRIu32 " results, expected one GRAVITY_FORCES", reply->results._length);
        }
        const wbi_msg_OperationResult* result = &reply->results._buffer[0];
        printf("model: GRAVITY_FORCES %" PRIu32 " x %" PRIu32 " in %.1f ms (server %.1f us)\n",
               result->rows, result->cols, (double)(dds_time() - sent) * 1e-6,
               (double)reply->compute_ns * 1e-3);
        printf("gravity_forces:");
        for (uint32_t k = 0; k < result->data._length; ++k) {
          printf(" %.17g", result->data._buffer[k]);
        }
        printf("\n");
        dds_return_loan(replies, samples, count);
        dds_delete(waitset);
        dds_delete(requests);
        dds_delete(replies);
        return;
      }
      if (count > 0) {
        dds_return_loan(replies, samples, count);
      }
      if (dds_time() > deadline) {
        fail("model: no reply within %.0f s", options->timeout_s);
      }
      dds_waitset_wait_until(waitset, NULL, 0, resend_at);
    }
  }
}

int main(int argc, char** argv) {
  const Options options = parse_options(argc, argv);
  setvbuf(stdout, NULL, _IOLBF, 0);
  const dds_entity_t participant =
      dds_create_participant((dds_domainid_t)options.domain, NULL, NULL);
  check_dds(participant, "create participant");
  printf("cyclone dds %s, domain %d, robot '%s'\n", DDS_VERSION, options.domain, options.robot);

  char joint_names[wbi_msg_MAX_JOINTS][wbi_msg_MAX_NAME + 1];
  const uint32_t joints = check_description(participant, &options, joint_names);
  check_streams(participant, &options, joints);
  check_command(participant, &options, joints, joint_names);
  check_status(participant, &options);
  if (options.gravity_joints > 0) {
    check_model(participant, &options);
  }
  dds_delete(participant);
  printf("interop: every check passed\n");
  return 0;
}
