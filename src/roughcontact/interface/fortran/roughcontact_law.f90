! roughcontact_law.f90 -- the interface law of section 8 of Buczkowski & Kleiber (2009) in Fortran:
! the tabulated statistical normal law p_N(u_N) and the orthotropic (8.1) / isotropic (8.2)
! slip-hardening friction return mapping with its consistent tangent.
!
! A line-by-line port of roughcontact.interface.kernels (the numba kernels behind
! roughcontact.interface.friction.update): the same algorithm, iterations, tolerances, tails and
! operation order, so that both agree to round-off (tests/interface/test_fortran_law.py drives
! both along the same paths). The algorithm, the errata and THE sign convention are documented
! in roughcontact/interface/friction.py's module docstring; equation numbers are the paper's.
!
! Conventions (as friction.py):
!   u_N  normal closure (> 0 closes), measured from the law's reference state h_ref;
!   p_N  >= 0 the contact pressure (positive in compression);
!   state(9) = (t_x, t_y, p_N, u_N, u_x^p, u_y^p, kappa_x, kappa_y, D) -- 1-based RC_T_X ...;
!   du(3) = (du_Tx, du_Ty, du_N); D(3,3) = d(t_x, t_y, p_N)/d(du_Tx, du_Ty, du_N).
!   tab(n, 4): rows (h, q = ln(W/A0), q', q'') with h ascending (NormalLawTable.kernel_table);
!   n = 0: the constant normal stiffness law (stiff = (k_Tx, k_Ty, k_N)); with a table
!   stiff = (k_Tx/k_N, k_Ty/k_N, unused).
!   model: RC_NO_LIMIT (par(1) = 0 frictionless, 1 no slip), RC_ISOTROPIC
!   (par = mu_m, mu_o, n), RC_ORTHOTROPIC (par = mu_m_x, mu_m_y, mu_o_x, mu_o_y, n_x, n_y, k).
!
! Free-form Fortran 95, implicit none, double precision throughout; compile without fast-math
! (gfortran -O2; ifort -fp-model precise) or round-off agreement is lost.
module roughcontact_law
  implicit none
  private

  integer, parameter, public :: rc_dp = kind(1.0d0)
  integer, parameter, public :: RC_NSTATE = 9
  integer, parameter, public :: RC_T_X = 1, RC_T_Y = 2, RC_T_N = 3, RC_U_N = 4, RC_UP_X = 5, &
       RC_UP_Y = 6, RC_KAPPA_X = 7, RC_KAPPA_Y = 8, RC_DISSIPATION = 9
  integer, parameter, public :: RC_KAPPA = RC_KAPPA_X  ! isotropic: the slip length
  integer, parameter, public :: RC_STICK = 0, RC_SLIP = 1, RC_OPEN = 2, RC_FAILED = -1, RC_BEYOND = -2
  integer, parameter, public :: RC_FORM_END = 0, RC_FORM_START = 1, RC_FORM_SECANT = 2
  integer, parameter, public :: RC_NO_LIMIT = 0, RC_ISOTROPIC = 1, RC_ORTHOTROPIC = 2

  integer, parameter :: MAXIT = 200
  real(rc_dp), parameter :: EPS = epsilon(1.0_rc_dp)  ! 2.220446049250313e-16, as the kernels

  ! the work vector of ortho_eval (kernels._E_*, 1-based)
  integer, parameter :: E_TX = 1, E_TY = 2, E_KX = 3, E_KY = 4, E_WX = 5, E_WY = 6, E_CX = 7, &
       E_CY = 8, E_S = 9, E_PHI = 10, E_S_LAM = 11, E_S_R = 12, E_S_TTX = 13, E_S_TTY = 14, &
       E_PHI_LAM = 15, E_PHI_R = 16, E_PHI_TTX = 17, E_PHI_TTY = 18, E_TX_LAM = 19, E_TX_R = 20, &
       E_TY_LAM = 21, E_TY_R = 22, E_S_KTX = 23, E_S_KTY = 24, E_PHI_KTX = 25, E_PHI_KTY = 26, &
       E_TX_KTX = 27, E_TY_KTY = 28, NE = 28

  public :: rc_closure_law, rc_update

contains

  ! ------------------------------------------------------------------------------------------
  ! the tabulated normal law (kernels.closure_law)
  ! ------------------------------------------------------------------------------------------
  subroutine rc_closure_law(u_n, h_ref, tab, p, dp, ddp, beyond)
    ! p_N [unit of E*], dp_N/du_N, d2p_N/du_N2 at the closure u_N = h_ref - h [L]; beyond is
    ! .true. (values 0) below the heavy end h < h_min. Light end: the C1 quadratic tail
    ! p = p_light z**2 down to open contact at z = 0 (normal_law.py, "Outside the table").
    real(rc_dp), intent(in) :: u_n, h_ref, tab(:, :)
    real(rc_dp), intent(out) :: p, dp, ddp
    logical, intent(out) :: beyond
    integer :: n, lo, hi, mid
    real(rc_dp) :: h, h_light, d_light, z, p_light, width, t, t2, t3
    real(rc_dp) :: g0, h1, g1, h2, g2, dg0, dh1, dg1, dh2, dg2, ddg0, ddh1, ddg1, ddh2, ddg2
    real(rc_dp) :: jump, s0, s1, c0, c1, q, dq, ddq

    n = size(tab, 1)
    h = h_ref - u_n
    p = 0.0_rc_dp
    dp = 0.0_rc_dp
    ddp = 0.0_rc_dp
    beyond = .false.
    if (h < tab(1, 1)) then
      beyond = .true.
      return
    end if
    h_light = tab(n, 1)
    if (h > h_light) then
      d_light = tab(n, 3)
      z = 1.0_rc_dp + 0.5_rc_dp * d_light * (h - h_light)
      if (z <= 0.0_rc_dp) return
      p_light = exp(tab(n, 2))
      p = p_light * z * z
      dp = -p_light * d_light * z
      ddp = 0.5_rc_dp * p_light * d_light * d_light
      return
    end if
    lo = 1
    hi = n
    do while (hi - lo > 1)  ! bisection for tab(lo, 1) <= h <= tab(lo + 1, 1)
      mid = (lo + hi) / 2
      if (tab(mid, 1) <= h) then
        lo = mid
      else
        hi = mid
      end if
    end do
    width = tab(lo + 1, 1) - tab(lo, 1)
    t = (h - tab(lo, 1)) / width
    t2 = t * t
    t3 = t2 * t
    ! quintic Hermite basis: G0 (value at 1; H0 = 1 - G0), H1/G1 (slopes), H2/G2 (curvatures)
    g0 = t3 * (10.0_rc_dp - 15.0_rc_dp * t + 6.0_rc_dp * t2)
    h1 = t - t3 * (6.0_rc_dp - 8.0_rc_dp * t + 3.0_rc_dp * t2)
    g1 = -t3 * (4.0_rc_dp - 7.0_rc_dp * t + 3.0_rc_dp * t2)
    h2 = 0.5_rc_dp * t2 * (1.0_rc_dp - 3.0_rc_dp * t + 3.0_rc_dp * t2 - t3)
    g2 = 0.5_rc_dp * t3 * (1.0_rc_dp - 2.0_rc_dp * t + t2)
    dg0 = 30.0_rc_dp * t2 * (1.0_rc_dp - 2.0_rc_dp * t + t2)
    dh1 = 1.0_rc_dp - t2 * (18.0_rc_dp - 32.0_rc_dp * t + 15.0_rc_dp * t2)
    dg1 = -t2 * (12.0_rc_dp - 28.0_rc_dp * t + 15.0_rc_dp * t2)
    dh2 = 0.5_rc_dp * t * (2.0_rc_dp - 9.0_rc_dp * t + 12.0_rc_dp * t2 - 5.0_rc_dp * t3)
    dg2 = 0.5_rc_dp * t2 * (3.0_rc_dp - 8.0_rc_dp * t + 5.0_rc_dp * t2)
    ddg0 = 60.0_rc_dp * t * (1.0_rc_dp - 3.0_rc_dp * t + 2.0_rc_dp * t2)
    ddh1 = -t * (36.0_rc_dp - 96.0_rc_dp * t + 60.0_rc_dp * t2)
    ddg1 = -t * (24.0_rc_dp - 84.0_rc_dp * t + 60.0_rc_dp * t2)
    ddh2 = 1.0_rc_dp - 9.0_rc_dp * t + 18.0_rc_dp * t2 - 10.0_rc_dp * t3
    ddg2 = t * (3.0_rc_dp - 12.0_rc_dp * t + 10.0_rc_dp * t2)
    jump = tab(lo + 1, 2) - tab(lo, 2)
    s0 = width * tab(lo, 3)
    s1 = width * tab(lo + 1, 3)
    c0 = width * width * tab(lo, 4)
    c1 = width * width * tab(lo + 1, 4)
    q = tab(lo, 2) + jump * g0 + s0 * h1 + s1 * g1 + c0 * h2 + c1 * g2
    dq = (jump * dg0 + s0 * dh1 + s1 * dg1 + c0 * dh2 + c1 * dg2) / width
    ddq = (jump * ddg0 + s0 * ddh1 + s1 * ddg1 + c0 * ddh2 + c1 * ddg2) / (width * width)
    p = exp(q)
    ! u = h_ref - h: dp/du = -p q', d2p/du2 = p (q'**2 + q'')
    dp = -p * dq
    ddp = p * (dq * dq + ddq)
  end subroutine rc_closure_law

  subroutine normal_law(u_n, k_n, tab, h_ref, p, dp, ddp, beyond)
    ! kernels._normal_law: the table, or (empty table) eq. (117) with constant k_N, open for u_N <= 0
    real(rc_dp), intent(in) :: u_n, k_n, tab(:, :), h_ref
    real(rc_dp), intent(out) :: p, dp, ddp
    logical, intent(out) :: beyond
    if (size(tab, 1) > 0) then
      call rc_closure_law(u_n, h_ref, tab, p, dp, ddp, beyond)
      return
    end if
    beyond = .false.
    ddp = 0.0_rc_dp
    if (u_n > 0.0_rc_dp) then
      p = k_n * u_n
      dp = k_n
    else
      p = 0.0_rc_dp
      dp = 0.0_rc_dp
    end if
  end subroutine normal_law

  subroutine hardening(mu_m, mu_o, n, kappa, mu, dmu)
    real(rc_dp), intent(in) :: mu_m, mu_o, n, kappa
    real(rc_dp), intent(out) :: mu, dmu
    real(rc_dp) :: e
    e = exp(-n * kappa)
    mu = mu_m * (1.0_rc_dp - (1.0_rc_dp - mu_o) * e)  ! eq. (89)/(90)/(119)
    dmu = n * mu_m * (1.0_rc_dp - mu_o) * e  ! eq. (111)/(112)/(129)
  end subroutine hardening

  pure real(rc_dp) function sgn(x)
    real(rc_dp), intent(in) :: x
    if (x > 0.0_rc_dp) then
      sgn = 1.0_rc_dp
    else if (x < 0.0_rc_dp) then
      sgn = -1.0_rc_dp
    else
      sgn = 0.0_rc_dp
    end if
  end function sgn

  ! ------------------------------------------------------------------------------------------
  ! the orthotropic return mapping (section 8.1; kernels._ortho_eval, _ortho_solve_r)
  ! ------------------------------------------------------------------------------------------
  subroutine ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, out)
    ! backward-Euler state at (lambda, r) and the partial derivatives of F = S - p and
    ! Phi = r - k ln(mu_y/mu_x) in lambda, r, the trial tractions and k_Tx, k_Ty
    real(rc_dp), intent(in) :: lam, r, ttx, tty, ktx, kty, kxn, kyn, par(:)
    real(rc_dp), intent(out) :: out(NE)
    real(rc_dp) :: wx, wy, cx, cy, tx, ty, ax, ay, kx, ky, mux, dmux, muy, dmuy, hx, hy, ke
    real(rc_dp) :: cx_lam, cx_r, cy_lam, cy_r, tx_lam, tx_r, ty_lam, ty_r
    real(rc_dp) :: kx_lam, kx_r, kx_ttx, ky_lam, ky_r, ky_tty
    real(rc_dp) :: phi, phi_lam, phi_r, phi_ttx, phi_tty, s, gx, gy
    real(rc_dp) :: cx_k, cy_k, tx_k, ty_k, kx_k, ky_k

    wx = exp(r)
    wy = exp(-r)
    cx = 1.0_rc_dp / (1.0_rc_dp + ktx * lam * wx)
    cy = 1.0_rc_dp / (1.0_rc_dp + kty * lam * wy)
    tx = ttx * cx  ! t = t^tr - K_T du^p, du_i^p = lambda w_i t_i: eqs. (93), (99)
    ty = tty * cy
    ax = abs(ttx)
    ay = abs(tty)
    kx = kxn + ax * lam * wx * cx  ! kappa_i = kappa_i,n + |du_i^p|
    ky = kyn + ay * lam * wy * cy
    call hardening(par(1), par(3), par(5), kx, mux, dmux)  ! eq. (89), (111)
    call hardening(par(2), par(4), par(6), ky, muy, dmuy)  ! eq. (90), (112)
    hx = dmux / mux
    hy = dmuy / muy
    ke = par(7)
    cx_lam = -ktx * wx * cx * cx
    cx_r = -ktx * lam * wx * cx * cx
    cy_lam = -kty * wy * cy * cy
    cy_r = kty * lam * wy * cy * cy
    tx_lam = ttx * cx_lam
    tx_r = ttx * cx_r
    ty_lam = tty * cy_lam
    ty_r = tty * cy_r
    kx_lam = ax * wx * cx * cx
    kx_r = ax * lam * wx * cx * cx
    kx_ttx = sgn(ttx) * lam * wx * cx
    ky_lam = ay * wy * cy * cy
    ky_r = -ay * lam * wy * cy * cy
    ky_tty = sgn(tty) * lam * wy * cy
    ! Phi: potential ratio nu_y/nu_x = (mu_y/mu_x)**k, eq. (98), in logarithms
    phi = r - ke * (log(muy) - log(mux))
    phi_lam = -ke * (hy * ky_lam - hx * kx_lam)
    phi_r = 1.0_rc_dp - ke * (hy * ky_r - hx * kx_r)
    phi_ttx = ke * hx * kx_ttx
    phi_tty = -ke * hy * ky_tty
    ! limit function, eq. (91); dS/dt_i = c_x, c_y of eq. (106)
    s = sqrt((tx / mux)**2 + (ty / muy)**2)
    gx = tx / (mux * mux * s)
    gy = ty / (muy * muy * s)
    out(E_TX) = tx
    out(E_TY) = ty
    out(E_KX) = kx
    out(E_KY) = ky
    out(E_WX) = wx
    out(E_WY) = wy
    out(E_CX) = cx
    out(E_CY) = cy
    out(E_S) = s
    out(E_PHI) = phi
    out(E_S_LAM) = gx * (tx_lam - tx * hx * kx_lam) + gy * (ty_lam - ty * hy * ky_lam)
    out(E_S_R) = gx * (tx_r - tx * hx * kx_r) + gy * (ty_r - ty * hy * ky_r)
    out(E_S_TTX) = gx * (cx - tx * hx * kx_ttx)
    out(E_S_TTY) = gy * (cy - ty * hy * ky_tty)
    out(E_PHI_LAM) = phi_lam
    out(E_PHI_R) = phi_r
    out(E_PHI_TTX) = phi_ttx
    out(E_PHI_TTY) = phi_tty
    out(E_TX_LAM) = tx_lam
    out(E_TX_R) = tx_r
    out(E_TY_LAM) = ty_lam
    out(E_TY_R) = ty_r
    ! k_T-derivatives at fixed (lambda, r, t^tr): needed when k_T follows k_N(u_N)
    cx_k = -lam * wx * cx * cx
    cy_k = -lam * wy * cy * cy
    tx_k = ttx * cx_k
    ty_k = tty * cy_k
    kx_k = ax * lam * wx * cx_k
    ky_k = ay * lam * wy * cy_k
    out(E_S_KTX) = gx * (tx_k - tx * hx * kx_k)
    out(E_S_KTY) = gy * (ty_k - ty * hy * ky_k)
    out(E_PHI_KTX) = ke * hx * kx_k
    out(E_PHI_KTY) = -ke * hy * ky_k
    out(E_TX_KTX) = tx_k
    out(E_TY_KTY) = ty_k
  end subroutine ortho_eval

  subroutine ortho_solve_r(lam, r0, ttx, tty, ktx, kty, kxn, kyn, par, wk, tol, r, fail)
    ! Phi(r; lambda) = 0 by bracketed Newton; bracket: the range of k ln(mu_y/mu_x) over the box
    ! kappa_i in [kappa_i,n, kappa_i,n + |t_i^tr|/k_Ti] that contains every backward-Euler kappa
    real(rc_dp), intent(in) :: lam, r0, ttx, tty, ktx, kty, kxn, kyn, par(:), tol
    real(rc_dp), intent(out) :: wk(NE), r
    logical, intent(out) :: fail
    real(rc_dp) :: ke, mxa, mxb, mya, myb, dummy, lo_l, hi_l, lo, hi, phi, dphi, rn, cand
    logical :: newton, done
    integer :: it

    fail = .false.
    ke = par(7)
    if (ke == 0.0_rc_dp) then
      r = 0.0_rc_dp
      call ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk)
      return
    end if
    call hardening(par(1), par(3), par(5), kxn, mxa, dummy)
    call hardening(par(1), par(3), par(5), kxn + abs(ttx) / ktx, mxb, dummy)
    call hardening(par(2), par(4), par(6), kyn, mya, dummy)
    call hardening(par(2), par(4), par(6), kyn + abs(tty) / kty, myb, dummy)
    lo_l = log(min(mya, myb)) - log(max(mxa, mxb))
    hi_l = log(max(mya, myb)) - log(min(mxa, mxb))
    if (ke > 0.0_rc_dp) then
      lo = ke * lo_l
      hi = ke * hi_l
    else
      lo = ke * hi_l
      hi = ke * lo_l
    end if
    r = min(max(r0, lo), hi)
    if (hi - lo <= 0.0_rc_dp) then
      call ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk)
      return
    end if
    do it = 1, MAXIT
      call ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk)
      phi = wk(E_PHI)
      if (phi == 0.0_rc_dp) return
      if (phi < 0.0_rc_dp) then
        lo = r
      else
        hi = r
      end if
      dphi = wk(E_PHI_R)
      newton = .false.
      rn = 0.5_rc_dp * (lo + hi)
      if (dphi > 0.0_rc_dp) then
        cand = r - phi / dphi
        if (lo < cand .and. cand < hi) then
          rn = cand
          newton = .true.
        end if
      end if
      done = (newton .and. abs(rn - r) <= tol * (1.0_rc_dp + abs(rn))) .or. &
           (hi - lo) <= 4.0_rc_dp * EPS * (1.0_rc_dp + abs(rn))
      r = rn
      if (done) then
        call ortho_eval(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk)
        return
      end if
    end do
    fail = .true.
  end subroutine ortho_solve_r

  ! ------------------------------------------------------------------------------------------
  ! shared parts of the updates (kernels._begin_update, _stick, _assemble_tangent,
  ! _safeguarded_step)
  ! ------------------------------------------------------------------------------------------
  subroutine begin_update(stiff, s_old, du, s_new, d, tab, h_ref, form, status, p, dp, ttx, tty, &
       ktx, kty, dktx, dkty, lvx, lvy)
    ! copy the state, zero D, the normal law at the end of the step; for a closed contact the
    ! trial tangential tractions of the tangential form, eq. (93)-(94). status RC_OPEN,
    ! RC_BEYOND or RC_STICK (= closed, to decide). See kernels._begin_update.
    real(rc_dp), intent(in) :: stiff(3), s_old(RC_NSTATE), du(3), tab(:, :), h_ref
    integer, intent(in) :: form
    real(rc_dp), intent(out) :: s_new(RC_NSTATE), d(3, 3)
    integer, intent(out) :: status
    real(rc_dp), intent(out) :: p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy
    real(rc_dp) :: u_n, ddp, tnx, tny, ktx0, kty0, p0, dp0, ddp0
    logical :: beyond, beyond0

    s_new = s_old
    d = 0.0_rc_dp
    ttx = 0.0_rc_dp
    tty = 0.0_rc_dp
    ktx = 0.0_rc_dp
    kty = 0.0_rc_dp
    dktx = 0.0_rc_dp
    dkty = 0.0_rc_dp
    lvx = 0.0_rc_dp
    lvy = 0.0_rc_dp
    u_n = s_old(RC_U_N) + du(3)
    call normal_law(u_n, stiff(3), tab, h_ref, p, dp, ddp, beyond)
    s_new(RC_U_N) = u_n
    s_new(RC_T_N) = p
    if (beyond) then
      status = RC_BEYOND
      return
    end if
    if (p <= 0.0_rc_dp) then
      s_new(RC_T_X) = 0.0_rc_dp
      s_new(RC_T_Y) = 0.0_rc_dp
      status = RC_OPEN
      return
    end if
    status = RC_STICK
    tnx = s_old(RC_T_X)
    tny = s_old(RC_T_Y)
    if (size(tab, 1) > 0) then
      ktx = stiff(1) * dp
      kty = stiff(2) * dp
      dktx = stiff(1) * ddp
      dkty = stiff(2) * ddp
      ktx0 = ktx
      kty0 = kty
      if (form /= RC_FORM_END) then  ! K_T(u_N,n) = a k_N(u_N,n) at the start of the step
        call normal_law(s_old(RC_U_N), stiff(3), tab, h_ref, p0, dp0, ddp0, beyond0)
        if (beyond0) then
          ttx = 0.0_rc_dp
          tty = 0.0_rc_dp
          ktx = 0.0_rc_dp
          kty = 0.0_rc_dp
          dktx = 0.0_rc_dp
          dkty = 0.0_rc_dp
          status = RC_BEYOND
          return
        end if
        ktx0 = stiff(1) * dp0
        kty0 = stiff(2) * dp0
        if (dp0 <= 0.0_rc_dp) then  ! the start state was open: K_T,n = 0 and t_n = 0
          tnx = 0.0_rc_dp
          tny = 0.0_rc_dp
        end if
      end if
    else  ! constant k_T: all forms reduce to the end form bitwise
      ktx = stiff(1)
      kty = stiff(2)
      dktx = 0.0_rc_dp
      dkty = 0.0_rc_dp
      ktx0 = ktx
      kty0 = kty
    end if
    if (form == RC_FORM_START) then  ! k_T frozen at u_N,n: dt^tr/du_N = 0
      ttx = tnx + ktx0 * du(1)
      tty = tny + kty0 * du(2)
      ktx = ktx0
      kty = kty0
      dktx = 0.0_rc_dp
      dkty = 0.0_rc_dp
      lvx = 0.0_rc_dp
      lvy = 0.0_rc_dp
      return
    end if
    if (form == RC_FORM_SECANT) then  ! t^tr = t_n (K/K_n) + K du_T
      ttx = ktx * du(1)
      tty = kty * du(2)
      lvx = du(1)
      lvy = du(2)
      if (ktx0 > 0.0_rc_dp) then
        ttx = ttx + tnx * (ktx / ktx0)
        lvx = lvx + tnx / ktx0
      end if
      if (kty0 > 0.0_rc_dp) then
        tty = tty + tny * (kty / kty0)
        lvy = lvy + tny / kty0
      end if
      return
    end if
    ttx = tnx + ktx * du(1)
    tty = tny + kty * du(2)
    lvx = du(1)
    lvy = du(2)
  end subroutine begin_update

  subroutine stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, d)
    ! t = t^tr, D = D^e (94) plus dt^tr/du_N = dK_T/du_N e (lever e of begin_update)
    real(rc_dp), intent(in) :: ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy
    real(rc_dp), intent(inout) :: s_new(RC_NSTATE), d(3, 3)
    s_new(RC_T_X) = ttx
    s_new(RC_T_Y) = tty
    d(1, 1) = ktx
    d(2, 2) = kty
    d(3, 3) = dp
    if (dktx /= 0.0_rc_dp .or. dkty /= 0.0_rc_dp) then
      d(1, 3) = dktx * lvx
      d(2, 3) = dkty * lvy
    end if
  end subroutine stick

  subroutine assemble_tangent(sens, ktx, kty, dp, dktx, dkty, lvx, lvy, d)
    ! D rows t_x, t_y from sens(i, m) = dt_i/dtheta_m, theta = (t^tr_x, t^tr_y, p, k_Tx, k_Ty),
    ! by the chain rule (kernels._assemble_tangent); row p_N: dp/du_N
    real(rc_dp), intent(in) :: sens(2, 5), ktx, kty, dp, dktx, dkty, lvx, lvy
    real(rc_dp), intent(inout) :: d(3, 3)
    integer :: i
    do i = 1, 2
      d(i, 1) = sens(i, 1) * ktx
      d(i, 2) = sens(i, 2) * kty
      d(i, 3) = sens(i, 3) * dp
      if (dktx /= 0.0_rc_dp .or. dkty /= 0.0_rc_dp) then
        d(i, 3) = d(i, 3) + (sens(i, 1) * lvx + sens(i, 4)) * dktx + (sens(i, 2) * lvy + sens(i, 5)) * dkty
      end if
    end do
    d(3, 3) = dp
  end subroutine assemble_tangent

  subroutine safeguarded_step(lam, psi, dpsi, lo, hi, first, tol, lam_new, done)
    ! one bracketed Newton step for lambda >= 0 on psi(lambda) increasing from psi(0) < 0
    ! (hi < 0: no upper bracket yet); kernels._safeguarded_step
    real(rc_dp), intent(in) :: lam, psi, dpsi, first, tol
    real(rc_dp), intent(inout) :: lo, hi
    real(rc_dp), intent(out) :: lam_new
    logical, intent(out) :: done
    logical :: newton
    real(rc_dp) :: cand
    if (psi < 0.0_rc_dp) then
      lo = lam
    else
      hi = lam
    end if
    newton = .false.
    cand = 0.0_rc_dp
    if (dpsi > 0.0_rc_dp) then
      cand = lam - psi / dpsi
      if (cand > lo .and. (hi < 0.0_rc_dp .or. cand < hi)) newton = .true.
    end if
    if (.not. newton) then
      if (hi >= 0.0_rc_dp) then
        cand = 0.5_rc_dp * (lo + hi)
      else if (lam == 0.0_rc_dp) then
        cand = first
      else
        cand = 2.0_rc_dp * lam
      end if
    end if
    done = (newton .and. abs(cand - lam) <= tol * cand) .or. &
         (hi >= 0.0_rc_dp .and. hi - lo <= 4.0_rc_dp * EPS * hi)
    lam_new = cand
  end subroutine safeguarded_step

  ! ------------------------------------------------------------------------------------------
  ! the point updates (kernels._ortho_point, _iso_point, _no_limit_point)
  ! ------------------------------------------------------------------------------------------
  subroutine ortho_point(par, stiff, s_old, du, s_new, d, tol, tab, h_ref, form, status)
    ! one orthotropic update (section 8.1)
    real(rc_dp), intent(in) :: par(:), stiff(3), s_old(RC_NSTATE), du(3), tol, tab(:, :), h_ref
    integer, intent(in) :: form
    real(rc_dp), intent(out) :: s_new(RC_NSTATE), d(3, 3)
    integer, intent(out) :: status
    real(rc_dp) :: p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy
    real(rc_dp) :: kxn, kyn, mux, muy, dummy, s_tr, r, r_new, lam, lam_new, lo, hi, s, psi, drdl, dpsi, first
    real(rc_dp) :: tx, ty, dupx, dupy, a11, a12, a21, a22, det, dlam, dr
    real(rc_dp) :: wk(NE), b1(5), b2(5), ex(5), ey(5), sens(2, 5)
    logical :: fail, done
    integer :: it, m

    call begin_update(stiff, s_old, du, s_new, d, tab, h_ref, form, status, p, dp, ttx, tty, &
         ktx, kty, dktx, dkty, lvx, lvy)
    if (status /= RC_STICK) return
    kxn = s_old(RC_KAPPA_X)
    kyn = s_old(RC_KAPPA_Y)
    call hardening(par(1), par(3), par(5), kxn, mux, dummy)
    call hardening(par(2), par(4), par(6), kyn, muy, dummy)
    s_tr = sqrt((ttx / mux)**2 + (tty / muy)**2)
    if (s_tr - p <= 0.0_rc_dp) then  ! f <= 0, eq. (91): stick
      call stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, d)
      status = RC_STICK
      return
    end if
    ! slip: backward-Euler return mapping; psi(lambda) = p/S - 1 increases from psi(0) < 0
    wk = 0.0_rc_dp
    r = par(7) * (log(muy) - log(mux))
    lam = 0.0_rc_dp
    lo = 0.0_rc_dp
    hi = -1.0_rc_dp  ! no upper bracket yet
    status = RC_FAILED
    do it = 1, MAXIT
      call ortho_solve_r(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk, 1.0e-14_rc_dp, r_new, fail)
      r = r_new
      if (fail) exit
      s = wk(E_S)
      psi = p / s - 1.0_rc_dp
      drdl = -wk(E_PHI_LAM) / wk(E_PHI_R)
      dpsi = -p / (s * s) * (wk(E_S_LAM) + wk(E_S_R) * drdl)
      if (psi == 0.0_rc_dp) then
        status = RC_SLIP
        exit
      end if
      if (lam == 0.0_rc_dp) then
        first = (s / p - 1.0_rc_dp) / max(ktx * wk(E_WX), kty * wk(E_WY))
      else
        first = 0.0_rc_dp
      end if
      call safeguarded_step(lam, psi, dpsi, lo, hi, first, tol, lam_new, done)
      lam = lam_new
      if (done) then
        call ortho_solve_r(lam, r, ttx, tty, ktx, kty, kxn, kyn, par, wk, 1.0e-14_rc_dp, r_new, fail)
        r = r_new
        if (.not. fail) status = RC_SLIP
        exit
      end if
    end do
    if (status == RC_FAILED) return
    tx = wk(E_TX)
    ty = wk(E_TY)
    dupx = lam * wk(E_WX) * tx  ! du^p = gamma dg/dt, eq. (99) with (98)/(101), du_N^p = 0
    dupy = lam * wk(E_WY) * ty
    s_new(RC_T_X) = tx
    s_new(RC_T_Y) = ty
    s_new(RC_UP_X) = s_old(RC_UP_X) + dupx
    s_new(RC_UP_Y) = s_old(RC_UP_Y) + dupy
    s_new(RC_KAPPA_X) = wk(E_KX)
    s_new(RC_KAPPA_Y) = wk(E_KY)
    s_new(RC_DISSIPATION) = s_old(RC_DISSIPATION) + tx * dupx + ty * dupy
    ! consistent tangent: implicit differentiation of (F, Phi) = 0 in (lambda, r)
    a11 = wk(E_S_LAM)
    a12 = wk(E_S_R)
    a21 = wk(E_PHI_LAM)
    a22 = wk(E_PHI_R)
    det = a11 * a22 - a12 * a21
    ! right-hand sides: theta = (t^tr_x, t^tr_y, p, k_Tx, k_Ty); F_p = -1, Phi_p = 0
    b1 = (/ wk(E_S_TTX), wk(E_S_TTY), -1.0_rc_dp, wk(E_S_KTX), wk(E_S_KTY) /)
    b2 = (/ wk(E_PHI_TTX), wk(E_PHI_TTY), 0.0_rc_dp, wk(E_PHI_KTX), wk(E_PHI_KTY) /)
    ! direct dt/dtheta at fixed (lambda, r)
    ex = (/ wk(E_CX), 0.0_rc_dp, 0.0_rc_dp, wk(E_TX_KTX), 0.0_rc_dp /)
    ey = (/ 0.0_rc_dp, wk(E_CY), 0.0_rc_dp, 0.0_rc_dp, wk(E_TY_KTY) /)
    do m = 1, 5
      dlam = -(a22 * b1(m) - a12 * b2(m)) / det
      dr = -(-a21 * b1(m) + a11 * b2(m)) / det
      sens(1, m) = wk(E_TX_LAM) * dlam + wk(E_TX_R) * dr + ex(m)
      sens(2, m) = wk(E_TY_LAM) * dlam + wk(E_TY_R) * dr + ey(m)
    end do
    call assemble_tangent(sens, ktx, kty, dp, dktx, dkty, lvx, lvy, d)
    status = RC_SLIP
  end subroutine ortho_point

  subroutine iso_eval(lam, ttx, tty, ktx, kty, kapn, par, tx, ty, cx, cy, t, kap, mu, dmu, &
       t_lam, kap_lam)
    real(rc_dp), intent(in) :: lam, ttx, tty, ktx, kty, kapn, par(:)
    real(rc_dp), intent(out) :: tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam
    cx = 1.0_rc_dp / (1.0_rc_dp + ktx * lam)
    cy = 1.0_rc_dp / (1.0_rc_dp + kty * lam)
    tx = ttx * cx  ! t = t^tr - K_T gamma t/|t|, eqs. (93), (99), (121); lambda = gamma/|t|
    ty = tty * cy
    t = sqrt(tx * tx + ty * ty)
    kap = kapn + lam * t  ! kappa = kappa_n + |du^p|, eq. (119)
    call hardening(par(1), par(2), par(3), kap, mu, dmu)  ! eq. (119), (129)
    t_lam = -(ktx * cx * tx * tx + kty * cy * ty * ty) / t
    kap_lam = t + lam * t_lam
  end subroutine iso_eval

  subroutine iso_point(par, stiff, s_old, du, s_new, d, tol, tab, h_ref, form, status)
    ! one isotropic update (section 8.2)
    real(rc_dp), intent(in) :: par(:), stiff(3), s_old(RC_NSTATE), du(3), tol, tab(:, :), h_ref
    integer, intent(in) :: form
    real(rc_dp), intent(out) :: s_new(RC_NSTATE), d(3, 3)
    integer, intent(out) :: status
    real(rc_dp) :: p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy
    real(rc_dp) :: kapn, mu0, dummy, lam, lam_new, lo, hi, psi, dpsi, first
    real(rc_dp) :: tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam, dupx, dupy
    real(rc_dp) :: f_lam, fac, txk, tyk, tx_lam, ty_lam, dlam
    real(rc_dp) :: b(5), ex(5), ey(5), sens(2, 5)
    logical :: done
    integer :: it, m

    call begin_update(stiff, s_old, du, s_new, d, tab, h_ref, form, status, p, dp, ttx, tty, &
         ktx, kty, dktx, dkty, lvx, lvy)
    if (status /= RC_STICK) return
    kapn = s_old(RC_KAPPA)
    call hardening(par(1), par(2), par(3), kapn, mu0, dummy)
    if (sqrt(ttx * ttx + tty * tty) - mu0 * p <= 0.0_rc_dp) then  ! f <= 0, eq. (120): stick
      call stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, d)
      status = RC_STICK
      return
    end if
    lam = 0.0_rc_dp
    lo = 0.0_rc_dp
    hi = -1.0_rc_dp
    status = RC_FAILED
    do it = 1, MAXIT
      call iso_eval(lam, ttx, tty, ktx, kty, kapn, par, tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam)
      psi = mu * p / t - 1.0_rc_dp
      dpsi = p * (dmu * kap_lam * t - mu * t_lam) / (t * t)
      if (psi == 0.0_rc_dp) then
        status = RC_SLIP
        exit
      end if
      if (lam == 0.0_rc_dp) then
        first = (t / (mu * p) - 1.0_rc_dp) / max(ktx, kty)
      else
        first = 0.0_rc_dp
      end if
      call safeguarded_step(lam, psi, dpsi, lo, hi, first, tol, lam_new, done)
      lam = lam_new
      if (done) then
        status = RC_SLIP
        exit
      end if
    end do
    if (status == RC_FAILED) return
    call iso_eval(lam, ttx, tty, ktx, kty, kapn, par, tx, ty, cx, cy, t, kap, mu, dmu, t_lam, kap_lam)
    dupx = lam * tx  ! du^p = gamma t/|t|, eq. (99) with (121)
    dupy = lam * ty
    s_new(RC_T_X) = tx
    s_new(RC_T_Y) = ty
    s_new(RC_UP_X) = s_old(RC_UP_X) + dupx
    s_new(RC_UP_Y) = s_old(RC_UP_Y) + dupy
    s_new(RC_KAPPA) = kap
    s_new(RC_DISSIPATION) = s_old(RC_DISSIPATION) + tx * dupx + ty * dupy
    ! consistent tangent: F = |t| - mu_F p = 0 differentiated in lambda and
    ! theta = (t^tr_x, t^tr_y, p, k_Tx, k_Ty); d|t|/dk_Ti = -lambda c_i t_i**2/|t| at fixed lambda
    f_lam = t_lam - dmu * p * kap_lam
    fac = 1.0_rc_dp - dmu * p * lam
    txk = -lam * cx * tx
    tyk = -lam * cy * ty
    b = (/ tx * cx / t * fac, ty * cy / t * fac, -mu, tx * txk / t * fac, ty * tyk / t * fac /)
    ex = (/ cx, 0.0_rc_dp, 0.0_rc_dp, txk, 0.0_rc_dp /)
    ey = (/ 0.0_rc_dp, cy, 0.0_rc_dp, 0.0_rc_dp, tyk /)
    tx_lam = -ktx * cx * tx
    ty_lam = -kty * cy * ty
    do m = 1, 5
      dlam = -b(m) / f_lam
      sens(1, m) = tx_lam * dlam + ex(m)
      sens(2, m) = ty_lam * dlam + ey(m)
    end do
    call assemble_tangent(sens, ktx, kty, dp, dktx, dkty, lvx, lvy, d)
    status = RC_SLIP
  end subroutine iso_point

  subroutine no_limit_point(par, stiff, s_old, du, s_new, d, tab, h_ref, form, status)
    ! par(1) = 0 frictionless (t_T = 0, D = diag(0, 0, k_N)); par(1) = 1 no slip (stick always)
    real(rc_dp), intent(in) :: par(:), stiff(3), s_old(RC_NSTATE), du(3), tab(:, :), h_ref
    integer, intent(in) :: form
    real(rc_dp), intent(out) :: s_new(RC_NSTATE), d(3, 3)
    integer, intent(out) :: status
    real(rc_dp) :: p, dp, ttx, tty, ktx, kty, dktx, dkty, lvx, lvy

    call begin_update(stiff, s_old, du, s_new, d, tab, h_ref, form, status, p, dp, ttx, tty, &
         ktx, kty, dktx, dkty, lvx, lvy)
    if (status /= RC_STICK) return
    if (par(1) == 0.0_rc_dp) then
      s_new(RC_T_X) = 0.0_rc_dp
      s_new(RC_T_Y) = 0.0_rc_dp
      d(3, 3) = dp
      status = RC_SLIP
      return
    end if
    call stick(ttx, tty, ktx, kty, dp, dktx, dkty, lvx, lvy, s_new, d)
    status = RC_STICK
  end subroutine no_limit_point

  ! ------------------------------------------------------------------------------------------
  ! the entry point
  ! ------------------------------------------------------------------------------------------
  subroutine rc_update(model, par, stiff, s_old, du, s_new, d, tol, tab, h_ref, form, status)
    ! One increment of the interface law at one point (friction.update for one row):
    ! model RC_NO_LIMIT | RC_ISOTROPIC | RC_ORTHOTROPIC with its par (module header), stiff,
    ! the state at the start s_old(9), the increment du(3) = (du_Tx, du_Ty, du_N closure);
    ! out: s_new(9), the consistent tangent d(3,3) and status RC_STICK, RC_SLIP, RC_OPEN, or
    ! RC_BEYOND (closure past the heavy end of the table), RC_FAILED (no convergence), or
    ! RC_FAILED for an unknown model. tol: relative Newton step tolerance (friction.update: 1e-12).
    integer, intent(in) :: model, form
    real(rc_dp), intent(in) :: par(:), stiff(3), s_old(RC_NSTATE), du(3), tol, tab(:, :), h_ref
    real(rc_dp), intent(out) :: s_new(RC_NSTATE), d(3, 3)
    integer, intent(out) :: status
    select case (model)
    case (RC_ORTHOTROPIC)
      call ortho_point(par, stiff, s_old, du, s_new, d, tol, tab, h_ref, form, status)
    case (RC_ISOTROPIC)
      call iso_point(par, stiff, s_old, du, s_new, d, tol, tab, h_ref, form, status)
    case (RC_NO_LIMIT)
      call no_limit_point(par, stiff, s_old, du, s_new, d, tab, h_ref, form, status)
    case default
      s_new = s_old
      d = 0.0_rc_dp
      status = RC_FAILED
    end select
  end subroutine rc_update

end module roughcontact_law
