#include "wbi/model/data.hpp"

namespace wbi::model {

Data::Data(const Model& model)
    : R_WB(static_cast<std::size_t>(model.n_bodies), Matrix3d::Identity()),
      p_WB(static_cast<std::size_t>(model.n_bodies), Vector3d::Zero()),
      S(static_cast<std::size_t>(model.n_bodies), Vector6d::Zero()),
      support(static_cast<std::size_t>(model.n_bodies), 0),
      I_W(static_cast<std::size_t>(model.n_bodies)),
      I_C(static_cast<std::size_t>(model.n_bodies)),
      F(Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, model.n_bodies)),
      v(static_cast<std::size_t>(model.n_bodies), Vector6d::Zero()),
      a(static_cast<std::size_t>(model.n_bodies), Vector6d::Zero()),
      f(static_cast<std::size_t>(model.n_bodies), Vector6d::Zero()),
      IA(static_cast<std::size_t>(model.n_bodies), Matrix6d::Zero()),
      pA(static_cast<std::size_t>(model.n_bodies), Vector6d::Zero()),
      c(static_cast<std::size_t>(model.n_bodies), Vector6d::Zero()),
      U(static_cast<std::size_t>(model.n_bodies), Vector6d::Zero()),
      D(static_cast<std::size_t>(model.n_bodies), 0.0),
      u(static_cast<std::size_t>(model.n_bodies), 0.0),
      M(Eigen::MatrixXd::Zero(model.nv, model.nv)),
      tau(Eigen::VectorXd::Zero(model.nv)),
      h(Eigen::VectorXd::Zero(model.nv)),
      g(Eigen::VectorXd::Zero(model.nv)),
      ddq(Eigen::VectorXd::Zero(model.nv)),
      J(Eigen::MatrixXd::Zero(6, model.nv)),
      dJnu(Vector6d::Zero()),
      Ag(Eigen::MatrixXd::Zero(6, model.nv)),
      hg(Vector6d::Zero()),
      com(Vector3d::Zero()),
      J_com(Eigen::MatrixXd::Zero(3, model.nv)),
      dJnu_com(Vector3d::Zero()) {}

}  // namespace wbi::model
