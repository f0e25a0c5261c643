! rc_ccx_element.f90 -- the engine's zero-thickness interface element as a CalculiX 2.20 *USER ELEMENT
! (types URCQ8: 8 + 8 nodes between the 8-node faces of C3D20, URCT6: 6 + 6 nodes between the
! 6-node faces of C3D10), carrying the interface law of roughcontact_law.f90.
!
! The element is data: everything that differs between elements and laws arrives in the deck's
! *USER SECTION constants, written by roughcontact.ccx.deck_rewrite from the library's own objects
! (the face element's shape functions and integration rule of roughcontact.fe, the law's table and
! friction parameters of roughcontact.interface.fortran_export). A value v_k is stored as the pair
! (hi, lo) = (v_k to 13 significant digits, v_k - hi): CalculiX reads a constant from 20 characters,
! too few for 17 digits, and hi + lo gives back the double exactly (docs/ccx.md).
!
! Geometry (roughcontact.fe.interface_points, the engine's convention): nodes 1..nf are side A
! (the master face), nf+1..2nf side B (the slave face, node nf+a facing node a). At an integration
! point q the jump is delta_q = R_q sum_a N_a (u_B,a - u_A,a) [deck length] with R_q rows
! (t1, t2, n): n = dx/dxi x dx/deta of side A normalised (the writer orders side A so that n points
! from master to slave), t1 the lay direction projected onto the face, t2 = n x t1. The law works in
! its own length unit and closes positive: du = law_per_deck * (d delta_1, d delta_2, -d delta_n);
! its tractions (t_x, t_y, p_N) are the engine's s = (t_x, t_y, -p_N) (friction.OPENING_SIGN).
! Forces f = sum_q w_q dA_q B_q^T s_q, tangent sum_q w_q dA_q B_q^T D_q B_q.
!
! The tangent is the law's consistent tangent, unsymmetric with friction: CalculiX 2.20 assembles
! the symmetric part of every element (mafillsm.f, rc_ccx_stiffness) and, when its flag nasym is
! set, adds unsymmetric contributions of its contact springs (mafillsmas.f). The build's patches
! set nasym where URC elements exist (nonlingeo.c) and add their antisymmetric part there
! (rc_ccx_antisymmetric), so Newton's matrix is the law's full tangent (docs/ccx.md).
!
! State per integration point (*DEPVAR, 14): 1-9 the law's state (roughcontact_law RC_T_X ...
! RC_DISSIPATION), 10-12 the jump delta [deck length] it was reached at, 13 the status
! (RC_STICK 0, RC_SLIP 1, RC_OPEN 2, RC_BEYOND -2), 14 = 1 once the point has been updated
! (a virgin point starts from the law's reference state: p_N = p_N(0), friction.initial_state).
! stx(1:3) = s [deck stress], stx(4:6) = delta [deck length]; xstiff(1:9) the tangent D_q (rows).
!
! Free-form Fortran 95, implicit none, double precision; compile with -frecursive (CalculiX calls
! the results routine from several threads: no saved locals).
module rc_ccx_element
  use roughcontact_law, only: rc_dp, rc_update, rc_closure_law, RC_NSTATE, RC_T_N, RC_FAILED
  implicit none
  private
  public :: rc_element_matrix, rc_element_results

  integer, parameter :: NDEP = 14, S_JUMP = 10, S_STATUS = 13, S_READY = 14
  integer, parameter :: MAXF = 8, MAXQ = 27
  ! the header of the decoded constants (roughcontact.ccx.deck_rewrite.HEADER)
  integer, parameter :: H_VERSION = 1, H_NFACE = 2, H_NQ = 3, H_MODEL = 4, H_FORM = 5, H_TOL = 6, &
       H_HREF = 7, H_SCALE = 8, H_LAY = 9, H_STIFF = 12, H_NPAR = 15, H_NTAB = 16, NHEAD = 16

contains

  pure function value_at(prop, i0, k) result(v)
    ! the k-th decoded constant of the section starting after prop(i0): hi + lo
    real(rc_dp), intent(in) :: prop(*)
    integer, intent(in) :: i0, k
    real(rc_dp) :: v
    v = prop(i0 + 2 * k - 1) + prop(i0 + 2 * k)
  end function value_at

  subroutine section(prop, i0, nf, nq, w, sh, dsh)
    ! the face element and its rule: nf nodes a side, nq points, weights w, N_a and dN_a/dxi_j
    real(rc_dp), intent(in) :: prop(*)
    integer, intent(in) :: i0
    integer, intent(out) :: nf, nq
    real(rc_dp), intent(out) :: w(MAXQ), sh(MAXF, MAXQ), dsh(2, MAXF, MAXQ)
    integer :: k, q, a, npar, ntab
    nf = nint(value_at(prop, i0, H_NFACE))
    nq = nint(value_at(prop, i0, H_NQ))
    if (nint(value_at(prop, i0, H_VERSION)) /= 1 .or. nf < 3 .or. nf > MAXF .or. nq < 1 .or. nq > MAXQ) then
      write (*, *) '*ERROR in rc_ccx_element: the *USER SECTION constants are not those of', &
           ' roughcontact ccx (version 1)'
      call exit(201)
    end if
    npar = nint(value_at(prop, i0, H_NPAR))
    ntab = nint(value_at(prop, i0, H_NTAB))
    k = NHEAD + npar + 4 * ntab
    do q = 1, nq
      k = k + 1
      w(q) = value_at(prop, i0, k)
      do a = 1, nf
        sh(a, q) = value_at(prop, i0, k + a)
        dsh(1, a, q) = value_at(prop, i0, k + nf + a)
        dsh(2, a, q) = value_at(prop, i0, k + 2 * nf + a)
      end do
      k = k + 3 * nf
    end do
  end subroutine section

  subroutine frame(xl, nf, dsh, lay, r, da)
    ! rows t1, t2, n of the local frame at one point and the area element |dx/dxi x dx/deta|
    ! (roughcontact.fe.interface_element.face_frame)
    real(rc_dp), intent(in) :: xl(3, *), dsh(2, MAXF), lay(3)
    integer, intent(in) :: nf
    real(rc_dp), intent(out) :: r(3, 3), da
    real(rc_dp) :: g1(3), g2(3), nrm(3), t1(3), s
    integer :: a
    g1 = 0.0_rc_dp
    g2 = 0.0_rc_dp
    do a = 1, nf
      g1 = g1 + dsh(1, a) * xl(:, a)
      g2 = g2 + dsh(2, a) * xl(:, a)
    end do
    nrm = cross(g1, g2)
    da = sqrt(sum(nrm * nrm))
    if (.not. (da > 0.0_rc_dp)) then
      write (*, *) '*ERROR in rc_ccx_element: a degenerate interface face'
      call exit(201)
    end if
    nrm = nrm / da
    t1 = lay - dot_product(nrm, lay) * nrm
    s = sqrt(sum(t1 * t1))
    if (s < 1.0e-8_rc_dp) then
      write (*, *) '*ERROR in rc_ccx_element: the lay direction is normal to an interface face'
      call exit(201)
    end if
    t1 = t1 / s
    r(1, :) = t1
    r(2, :) = cross(nrm, t1)
    r(3, :) = nrm
  end subroutine frame

  pure function cross(a, b) result(c)
    real(rc_dp), intent(in) :: a(3), b(3)
    real(rc_dp) :: c(3)
    c = (/ a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1) /)
  end function cross

  subroutine jump_operator(r, sh, nf, b)
    ! B (3, 6 nf): delta = B u_e, u_e the element's displacements (side A nodes, then side B)
    real(rc_dp), intent(in) :: r(3, 3), sh(MAXF)
    integer, intent(in) :: nf
    real(rc_dp), intent(out) :: b(3, 6 * MAXF)
    integer :: a
    b = 0.0_rc_dp
    do a = 1, nf
      b(:, 3 * (a - 1) + 1:3 * a) = -sh(a) * r
      b(:, 3 * (nf + a - 1) + 1:3 * (nf + a)) = sh(a) * r
    end do
  end subroutine jump_operator

  subroutine rc_element_matrix(co, kon, ipkon, nelem, ielprop, prop, mi, xstiff, part, s)
    ! sum_q w_q dA_q B_q^T D_q B_q over the element (6 nf x 6 nf of s(60, 60)) with D_q the law's
    ! tangent the results routine left in xstiff: its symmetric part (part = 1) or its
    ! antisymmetric part (part = -1; the two add up to the consistent tangent)
    integer, intent(in) :: kon(*), ipkon(*), nelem, ielprop(*), mi(*), part
    real(rc_dp), intent(in) :: co(3, *), prop(*), xstiff(27, mi(1), *)
    real(rc_dp), intent(inout) :: s(60, 60)
    real(rc_dp) :: w(MAXQ), sh(MAXF, MAXQ), dsh(2, MAXF, MAXQ), xl(3, 2 * MAXF), lay(3), r(3, 3), da
    real(rc_dp) :: b(3, 6 * MAXF), d(3, 3), db(3, 6 * MAXF)
    integer :: i0, nf, nq, q, a, n, i, j
    i0 = ielprop(nelem)
    call section(prop, i0, nf, nq, w, sh, dsh)
    do a = 1, 2 * nf
      xl(:, a) = co(:, kon(ipkon(nelem) + a))
    end do
    lay = (/ (value_at(prop, i0, H_LAY + i), i = 0, 2) /)
    n = 6 * nf
    s(1:n, 1:n) = 0.0_rc_dp
    do q = 1, nq
      call frame(xl, nf, dsh(:, :, q), lay, r, da)
      call jump_operator(r, sh(:, q), nf, b)
      do i = 1, 3
        do j = 1, 3
          d(i, j) = 0.5_rc_dp * (xstiff(3 * (i - 1) + j, q, nelem) + part * xstiff(3 * (j - 1) + i, q, nelem))
        end do
      end do
      db(:, 1:n) = matmul(d, b(:, 1:n))
      s(1:n, 1:n) = s(1:n, 1:n) + (w(q) * da) * matmul(transpose(b(:, 1:n)), db(:, 1:n))
    end do
  end subroutine rc_element_matrix

  subroutine rc_element_results(co, kon, ipkon, nelem, ielprop, prop, mi, v, nstate_, xstateini, xstate, &
       xstiff, stx, fn, calcul_fn, calcul_qa, qa, nal)
    ! the law at every point for the current displacements v: state, tractions, tangent, and the
    ! element's nodal forces added to fn (calcul_fn = 1), |forces| to qa(1) (calcul_qa = 1)
    integer, intent(in) :: kon(*), ipkon(*), nelem, ielprop(*), mi(*), nstate_, calcul_fn, calcul_qa
    integer, intent(inout) :: nal
    real(rc_dp), intent(in) :: co(3, *), prop(*), v(0:mi(2), *), xstateini(nstate_, mi(1), *)
    real(rc_dp), intent(inout) :: xstate(nstate_, mi(1), *), xstiff(27, mi(1), *), stx(6, mi(1), *), &
         fn(0:mi(2), *), qa(*)
    real(rc_dp) :: w(MAXQ), sh(MAXF, MAXQ), dsh(2, MAXF, MAXQ), xl(3, 2 * MAXF), ue(6 * MAXF), lay(3)
    real(rc_dp) :: r(3, 3), da, b(3, 6 * MAXF), delta(3), du(3), s_old(RC_NSTATE), s_new(RC_NSTATE)
    real(rc_dp) :: d(3, 3), trac(3), fe(6 * MAXF), stiff(3), par(16), scale, tol, h_ref, sg(3), p, dp, ddp
    real(rc_dp), allocatable :: tab(:, :)
    integer :: i0, nf, nq, q, a, i, j, model, form, npar, ntab, status
    logical :: beyond
    if (nstate_ < NDEP) then
      write (*, *) '*ERROR in rc_ccx_element: the interface material needs *DEPVAR', NDEP
      call exit(201)
    end if
    i0 = ielprop(nelem)
    call section(prop, i0, nf, nq, w, sh, dsh)
    model = nint(value_at(prop, i0, H_MODEL))
    form = nint(value_at(prop, i0, H_FORM))
    tol = value_at(prop, i0, H_TOL)
    h_ref = value_at(prop, i0, H_HREF)
    scale = value_at(prop, i0, H_SCALE)
    lay = (/ (value_at(prop, i0, H_LAY + i), i = 0, 2) /)
    stiff = (/ (value_at(prop, i0, H_STIFF + i), i = 0, 2) /)
    npar = nint(value_at(prop, i0, H_NPAR))
    ntab = nint(value_at(prop, i0, H_NTAB))
    if (npar < 1 .or. npar > size(par) .or. ntab < 2) then
      write (*, *) '*ERROR in rc_ccx_element: the law constants of element', nelem, ' are not a law'
      call exit(201)
    end if
    par(1:npar) = (/ (value_at(prop, i0, NHEAD + i), i = 1, npar) /)
    allocate (tab(ntab, 4))
    do i = 1, ntab
      do j = 1, 4
        tab(i, j) = value_at(prop, i0, NHEAD + npar + 4 * (i - 1) + j)
      end do
    end do
    do a = 1, 2 * nf
      xl(:, a) = co(:, kon(ipkon(nelem) + a))
      ue(3 * (a - 1) + 1:3 * a) = v(1:3, kon(ipkon(nelem) + a))
    end do
    sg = (/ 1.0_rc_dp, 1.0_rc_dp, -1.0_rc_dp /)  ! friction.OPENING_SIGN
    fe = 0.0_rc_dp
    do q = 1, nq
      call frame(xl, nf, dsh(:, :, q), lay, r, da)
      call jump_operator(r, sh(:, q), nf, b)
      delta = matmul(b(:, 1:6 * nf), ue(1:6 * nf))
      if (xstateini(S_READY, q, nelem) > 0.5_rc_dp) then
        s_old = xstateini(1:RC_NSTATE, q, nelem)
        du = scale * sg * (delta - xstateini(S_JUMP:S_JUMP + 2, q, nelem))
      else  ! virgin: the law's reference state u_N = 0, p_N = p_N(0) (friction.initial_state)
        s_old = 0.0_rc_dp
        call rc_closure_law(0.0_rc_dp, h_ref, tab, p, dp, ddp, beyond)
        s_old(RC_T_N) = p
        du = scale * sg * delta
      end if
      call rc_update(model, par(1:npar), stiff, s_old, du, s_new, d, tol, tab, h_ref, form, status)
      if (status == RC_FAILED) then
        write (*, *) '*ERROR in rc_ccx_element: the friction return mapping did not converge in element', &
             nelem, ' point', q
        call exit(201)
      end if
      trac = sg * s_new(1:3)
      xstate(1:RC_NSTATE, q, nelem) = s_new
      xstate(S_JUMP:S_JUMP + 2, q, nelem) = delta
      xstate(S_STATUS, q, nelem) = real(status, rc_dp)
      xstate(S_READY, q, nelem) = 1.0_rc_dp
      do i = 1, 3
        do j = 1, 3
          xstiff(3 * (i - 1) + j, q, nelem) = d(i, j) * sg(i) * sg(j) * scale
        end do
      end do
      stx(1:3, q, nelem) = trac
      stx(4:6, q, nelem) = delta
      fe(1:6 * nf) = fe(1:6 * nf) + (w(q) * da) * matmul(transpose(b(:, 1:6 * nf)), trac)
    end do
    deallocate (tab)
    if (calcul_fn == 1) then
      do a = 1, 2 * nf
        fn(1:3, kon(ipkon(nelem) + a)) = fn(1:3, kon(ipkon(nelem) + a)) + fe(3 * (a - 1) + 1:3 * a)
      end do
    end if
    if (calcul_qa == 1) then
      qa(1) = qa(1) + sum(abs(fe(1:6 * nf)))
      nal = nal + 6 * nf
    end if
  end subroutine rc_element_results

end module rc_ccx_element

! The entry points the patched dispatchers e_c3d_u.f and resultsmech_u.f call for lakon(2:3) = 'RC'
! (roughcontact.ccx.build.PATCHES): external procedures, so that fixed-form CalculiX needs no module.
subroutine rc_ccx_stiffness(co, kon, ipkon, nelem, ielprop, prop, mi, xstiff, s, ff, stiffness)
  ! e_c3d_u.f: the element matrix for CalculiX's symmetric assembly (mafillsm.f) and no loads
  use rc_ccx_element, only: rc_element_matrix
  implicit none
  integer, intent(in) :: kon(*), ipkon(*), nelem, ielprop(*), mi(*), stiffness
  double precision, intent(in) :: co(3, *), prop(*), xstiff(27, mi(1), *)
  double precision, intent(inout) :: s(60, 60), ff(60)
  ff = 0.0d0
  if (stiffness == 1) call rc_element_matrix(co, kon, ipkon, nelem, ielprop, prop, mi, xstiff, 1, s)
end subroutine rc_ccx_stiffness

subroutine rc_ccx_antisymmetric(co, kon, ipkon, nelem, ielprop, prop, mi, xstiff, s)
  ! mafillsmas.f: what the unsymmetric assembly adds to the symmetric part (nasym = 1)
  use rc_ccx_element, only: rc_element_matrix
  implicit none
  integer, intent(in) :: kon(*), ipkon(*), nelem, ielprop(*), mi(*)
  double precision, intent(in) :: co(3, *), prop(*), xstiff(27, mi(1), *)
  double precision, intent(inout) :: s(60, 60)
  call rc_element_matrix(co, kon, ipkon, nelem, ielprop, prop, mi, xstiff, -1, s)
end subroutine rc_ccx_antisymmetric

subroutine rc_ccx_results(co, kon, ipkon, nelem, ielprop, prop, mi, v, nstate_, xstateini, xstate, xstiff, stx, &
     fn, calcul_fn, calcul_qa, qa, nal)
  use rc_ccx_element, only: rc_element_results
  implicit none
  integer, intent(in) :: kon(*), ipkon(*), nelem, ielprop(*), mi(*), nstate_, calcul_fn, calcul_qa
  integer, intent(inout) :: nal
  double precision, intent(in) :: co(3, *), prop(*), v(0:mi(2), *), xstateini(nstate_, mi(1), *)
  double precision, intent(inout) :: xstate(nstate_, mi(1), *), xstiff(27, mi(1), *), stx(6, mi(1), *), &
       fn(0:mi(2), *), qa(*)
  call rc_element_results(co, kon, ipkon, nelem, ielprop, prop, mi, v, nstate_, xstateini, xstate, xstiff, stx, &
       fn, calcul_fn, calcul_qa, qa, nal)
end subroutine rc_ccx_results
