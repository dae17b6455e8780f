// Everything of the model library in one include.
#pragma once

#include "wbi/model/aba.hpp"
#include "wbi/model/centroidal.hpp"
#include "wbi/model/com.hpp"
#include "wbi/model/configuration.hpp"
#include "wbi/model/crba.hpp"
#include "wbi/model/data.hpp"
#include "wbi/model/jacobian.hpp"
#include "wbi/model/kinematics.hpp"
#include "wbi/model/model.hpp"
#include "wbi/model/rnea.hpp"
#include "wbi/model/urdf.hpp"
