/* What the checks of wbi_interop_cyclone share: options, errors and the DDS
 * entities as wbi's QoS profiles want them (idl/README.md, "Speaking wbi from
 * another DDS"). Cyclone DDS's C API only; the types are idlc's. */
#ifndef WBI_INTEROP_CYCLONE_H
#define WBI_INTEROP_CYCLONE_H

#include <stdbool.h>
#include <stdint.h>

#include <dds/dds.h>

#include "common.h"

enum { kTakeBatch = 64, kMaxSamples = 4096 }; /* a take; --samples at most */

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

/* Prints "wbi_interop_cyclone: <message>" on stderr and exits 1. */
void fail(const char* format, ...) __attribute__((format(printf, 1, 2), noreturn));
/* fail() when a DDS call returned an error. */
void check_dds(dds_return_t rc, const char* what);
dds_time_t deadline_after(double seconds);

/* A QoS; the entity functions below take (and delete) it. */
dds_qos_t* qos(dds_reliability_kind_t reliability, dds_durability_kind_t durability, int32_t depth);
/* Topic wbi/<robot>/<what>, or <what> when robot is NULL. */
dds_entity_t topic(dds_entity_t participant, const dds_topic_descriptor_t* type, const char* robot,
                   const char* what);
dds_entity_t reader(dds_entity_t participant, dds_entity_t t, dds_qos_t* q);
dds_entity_t writer(dds_entity_t participant, dds_entity_t t, dds_qos_t* q);
/* Waits until `entity` (a reader or a writer) has matched a remote endpoint. */
void wait_matched(dds_entity_t participant, dds_entity_t entity, bool is_writer, const char* what,
                  dds_time_t deadline);
/* A waitset that triggers when one of `readers` has data. */
dds_entity_t data_waitset(dds_entity_t participant, const dds_entity_t* readers, int count);
/* Waits until a reader of `waitset` has data; false at the deadline. */
bool wait_data(dds_entity_t waitset, dds_time_t deadline);
/* fail() unless the header names the robot. */
void check_robot(const wbi_msg_Header* header, const char* robot, const char* topic_name);

/* The checks, in the order main() runs them (one line each on stdout). */
uint32_t check_description(dds_entity_t participant, const Options* options,
                           char joint_names[][wbi_msg_MAX_NAME + 1]);
void check_streams(dds_entity_t participant, const Options* options, uint32_t joints);
void check_command(dds_entity_t participant, const Options* options, uint32_t joints,
                   char joint_names[][wbi_msg_MAX_NAME + 1]);
void check_status(dds_entity_t participant, const Options* options);
void check_model(dds_entity_t participant, const Options* options);

#endif
