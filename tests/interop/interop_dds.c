/* The DDS entities and errors every check of wbi_interop_cyclone uses. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interop.h"

void fail(const char* format, ...) {
  va_list args;
  va_start(args, format);
  fputs("wbi_interop_cyclone: ", stderr);
  vfprintf(stderr, format, args);
  fputc('\n', stderr);
  va_end(args);
  exit(1);
}

void check_dds(dds_return_t rc, const char* what) {
  if (rc < 0) {
    fail("%s: %s", what, dds_strretcode(rc));
  }
}

dds_time_t deadline_after(double seconds) { return dds_time() + (dds_duration_t)(seconds * 1e9); }

/* ---- QoS: what deploy/qos_profiles.xml gives wbi's writers (idl/README.md) ---- */

dds_qos_t* qos(dds_reliability_kind_t reliability, dds_durability_kind_t durability,
               int32_t depth) {
  dds_qos_t* q = dds_create_qos();
  dds_qset_reliability(q, reliability, DDS_SECS(1));
  dds_qset_durability(q, durability);
  dds_qset_history(q, DDS_HISTORY_KEEP_LAST, depth);
  return q;
}

dds_entity_t topic(dds_entity_t participant, const dds_topic_descriptor_t* type, const char* robot,
                   const char* what) {
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

dds_entity_t reader(dds_entity_t participant, dds_entity_t t, dds_qos_t* q) {
  const dds_entity_t r = dds_create_reader(participant, t, q, NULL);
  dds_delete_qos(q);
  check_dds(r, "create reader");
  return r;
}

dds_entity_t writer(dds_entity_t participant, dds_entity_t t, dds_qos_t* q) {
  const dds_entity_t w = dds_create_writer(participant, t, q, NULL);
  dds_delete_qos(q);
  check_dds(w, "create writer");
  return w;
}

/* Waits until `entity` (a reader or a writer) has matched a remote endpoint. */
void wait_matched(dds_entity_t participant, dds_entity_t entity, bool is_writer, const char* what,
                  dds_time_t deadline) {
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
bool wait_data(dds_entity_t waitset, dds_time_t deadline) {
  return dds_waitset_wait_until(waitset, NULL, 0, deadline) > 0;
}

dds_entity_t data_waitset(dds_entity_t participant, const dds_entity_t* readers, int count) {
  const dds_entity_t waitset = dds_create_waitset(participant);
  for (int i = 0; i < count; ++i) {
    const dds_entity_t condition = dds_create_readcondition(readers[i], DDS_ANY_STATE);
    check_dds(dds_waitset_attach(waitset, condition, readers[i]), "attach read condition");
  }
  return waitset;
}

void check_robot(const wbi_msg_Header* header, const char* robot, const char* topic_name) {
  if (strcmp(header->robot, robot) != 0) {
    fail("%s: header.robot '%s', expected '%s'", topic_name, header->robot, robot);
  }
}
