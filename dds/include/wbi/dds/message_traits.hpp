// Maps each wbi message type (generated from idl/) to its Fast DDS type
// support, so that Publisher<T> and Subscriber<T> need only T.
#pragma once

#include <memory>

#include <wbi/msg/claimsPubSubTypes.h>
#include <wbi/msg/commandsPubSubTypes.h>
#include <wbi/msg/controllersPubSubTypes.h>
#include <wbi/msg/descriptionPubSubTypes.h>
#include <wbi/msg/eventsPubSubTypes.h>
#include <wbi/msg/modelPubSubTypes.h>
#include <wbi/msg/playbackPubSubTypes.h>
#include <wbi/msg/referencesPubSubTypes.h>
#include <wbi/msg/sensorsPubSubTypes.h>
#include <wbi/msg/signalsPubSubTypes.h>
#include <wbi/msg/statePubSubTypes.h>
#include <wbi/msg/statusPubSubTypes.h>

namespace wbi::dds {

template <class T>
struct MessageTraits;  // specialised below for every top-level message

#define WBI_DDS_MESSAGE(Type)                                \
  template <>                                                \
  struct MessageTraits<wbi::msg::Type> {                     \
    using TypeSupport = wbi::msg::Type##PubSubType;          \
    static constexpr const char* kName = "wbi::msg::" #Type; \
  };

WBI_DDS_MESSAGE(RobotDescription)
WBI_DDS_MESSAGE(SensorSample)
WBI_DDS_MESSAGE(GroundTruth)
WBI_DDS_MESSAGE(ActuatorCommand)
WBI_DDS_MESSAGE(ControlParameters)
WBI_DDS_MESSAGE(StateEstimate)
WBI_DDS_MESSAGE(EstimatorParameter)
WBI_DDS_MESSAGE(ModelRequest)
WBI_DDS_MESSAGE(ModelReply)
WBI_DDS_MESSAGE(ComponentStatus)
WBI_DDS_MESSAGE(SimulationClock)
WBI_DDS_MESSAGE(PlaybackCommand)
WBI_DDS_MESSAGE(Signals)
WBI_DDS_MESSAGE(TrajectoryPoint)
WBI_DDS_MESSAGE(JointClaimRequest)
WBI_DDS_MESSAGE(JointClaimReply)
WBI_DDS_MESSAGE(JointOwners)
WBI_DDS_MESSAGE(ControllerRequest)
WBI_DDS_MESSAGE(ControllerReply)
WBI_DDS_MESSAGE(ControllerParameters)
WBI_DDS_MESSAGE(Event)

#undef WBI_DDS_MESSAGE

template <class T>
concept Message = requires {
  typename MessageTraits<T>::TypeSupport;
};

}  // namespace wbi::dds
