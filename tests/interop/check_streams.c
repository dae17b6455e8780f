/* The description, and the streams against the ground truth: encoders paired
 * by header.seq, the state estimate by header.stamp_ns. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "description.h"
#include "interop.h"
#include "sensors.h"
#include "state.h"

enum { kMaxRecords = 2 * kMaxSamples }; /* room for the samples that came before the wanted ones */

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

uint32_t check_description(dds_entity_t participant, const Options* options,
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

void check_streams(dds_entity_t participant, const Options* options, uint32_t joints) {
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
