! uinter.f90 -- Abaqus/Standard user subroutine UINTER for the rough-surface interface law of
! Buczkowski & Kleiber (2009), section 8: roughcontact_law.f90 (the law) with the data module
! roughcontact_law_data.f90 written by `roughcontact export-law LAW.yaml --format fortran`.
!
! Signature: as printed on the UINTER page of the Abaqus User Subroutines Reference Guide of
! the 2020s releases (Abaqus 2022: STRESS, DDSDDR, DVISCOUS, DSTRUCTURAL, FLUX, ... FREQR,
! CINAME, SLNAME (SECNAME), MSNAME (MAINNAME), ...); releases 6.x lack DVISCOUS, DSTRUCTURAL and
! FREQR. NOT RUN INSIDE ABAQUS: it is exercised by a gfortran harness only
! (tests/interface/test_fortran_law.py; docs/fortran-law.md).
!
! Abaqus conventions used (that page):
!   STRESS(1) the contact pressure, positive in compression; STRESS(2:NDIR) the shear stresses
!   along the local slip directions ALOCALDIR(:,2), ALOCALDIR(:,3);
!   RDISP(1) > 0 penetration (the law's closure u_N, in deck length), DRDISP its increment;
!   RDISP(2:NDIR), DRDISP(2:NDIR) relative tangential displacements and their increments;
!   DDSDDR(I,J) = d STRESS(I) / d DRDISP(J); STATEV passed in at the start of the increment;
!   LOPENCLOSE 0 open / 1 closed at the end of the increment; LSTATE the law's status at the end
!   (0 stick, 1 slip, 2 open); LSDI left as passed (the law is continuous: C1 normal law and
!   consistent tangent, no severe discontinuity to force); SFD the increment of frictional
!   dissipation per area; PNEWDT = 0.25 where the return mapping fails or the closure passes
!   even the tangent tail of the table (10**6 p_max).
! STATEV(1:9): the law's state in the law's units (the lay frame, lengths in the moments'
! unit): t_x, t_y, p_N, u_N, u_x^p, u_y^p, kappa_x, kappa_y, dissipation (*SURFACE INTERACTION,
! USER, DEPVAR=9). PROPS are not used (PROPERTIES=0): the law is compiled in.
! The law's x axis (the lay, rc_lay in the deck's axes) is projected on the tangent plane; its
! angle to ALOCALDIR(:,2) rotates the tangential components (the engine's convention:
! fe.interface_points, t1 along the lay).
subroutine uinter(stress, ddsddr, dviscous, dstructural, flux, ddfddt, ddsddt, ddfddr, statev, &
     sed, sfd, spd, svd, scd, pnewdt, rdisp, drdisp, temp, dtemp, predef, dpred, time, dtime, &
     freqr, ciname, slname, msname, props, coords, alocaldir, drot, area, chrlngth, node, ndir, &
     nstatv, npred, nprops, mcrd, kstep, kinc, kit, linper, lopenclose, lstate, lsdi, lprint)
  use roughcontact_law, only: rc_dp, rc_update, RC_NSTATE, RC_U_N, RC_T_X, RC_T_Y, RC_T_N, &
       RC_DISSIPATION, RC_STICK, RC_SLIP, RC_OPEN
  use roughcontact_law_data, only: rc_interaction, rc_model, rc_par, rc_stiff, rc_form, rc_tol, &
       rc_h_ref, rc_law_per_deck, rc_lay, rc_tab
  implicit none
  integer, intent(in) :: ndir, nstatv, npred, nprops, mcrd, kstep, kinc, kit, linper, lprint, node
  integer, intent(inout) :: lopenclose, lstate, lsdi
  real(rc_dp), intent(inout) :: stress(ndir), ddsddr(ndir, ndir), dviscous(ndir, ndir), &
       dstructural(ndir, ndir), flux(2), ddfddt(2, 2), ddsddt(ndir, 2), ddfddr(2, ndir), &
       statev(nstatv), sed, sfd, spd, svd, scd, pnewdt
  real(rc_dp), intent(in) :: rdisp(ndir), drdisp(ndir), temp(2), dtemp(2), predef(2, npred), &
       dpred(2, npred), time(2), dtime, freqr, props(nprops), coords(mcrd), alocaldir(3, 3), &
       drot(2, 2), area, chrlngth
  character(len=80), intent(in) :: ciname, slname, msname
  real(rc_dp) :: s_old(RC_NSTATE), s_new(RC_NSTATE), du(3), d(3, 3), q(2, 2), e1(3), nrm(3)
  real(rc_dp) :: c, s, length, d1, d2, dlay(3, 3)
  integer :: status, i, j

  if (trim(adjustl(ciname)) /= rc_interaction) then
    write (7, '(a)') 'roughcontact UINTER: interaction '//trim(adjustl(ciname))// &
         ' is not the compiled law '//rc_interaction//' (export that interaction)'
    call xit
  end if
  if (nstatv < RC_NSTATE .or. ndir < 2) then
    write (7, '(a)') 'roughcontact UINTER: needs DEPVAR >= 9 on *SURFACE INTERACTION, USER'
    call xit
  end if
  ! the lay frame in the local surface frame: e1 = lay projected on the tangent plane
  nrm = alocaldir(:, 1)
  e1 = rc_lay - dot_product(rc_lay, nrm) * nrm
  length = sqrt(dot_product(e1, e1))
  if (length <= 1.0e-8_rc_dp * sqrt(dot_product(rc_lay, rc_lay))) then
    write (7, '(a)') 'roughcontact UINTER: the lay direction is normal to the contact surface'
    call xit
  end if
  e1 = e1 / length
  c = dot_product(e1, alocaldir(:, 2))
  s = 0.0_rc_dp
  if (ndir > 2) s = dot_product(e1, alocaldir(:, 3))
  length = sqrt(c * c + s * s)
  c = c / length
  s = s / length
  q = reshape((/ c, s, -s, c /), (/ 2, 2 /))  ! lay-frame components -> local: v_loc = q v_lay
  ! the increment in the lay frame and law units: (du_Tx, du_Ty, du_N closure)
  d1 = drdisp(2)
  d2 = 0.0_rc_dp
  if (ndir > 2) d2 = drdisp(3)
  du(1) = (q(1, 1) * d1 + q(2, 1) * d2) * rc_law_per_deck
  du(2) = (q(1, 2) * d1 + q(2, 2) * d2) * rc_law_per_deck
  du(3) = drdisp(1) * rc_law_per_deck
  s_old = statev(1:RC_NSTATE)
  ! closure at the start of the increment from Abaqus's own positions (total, no drift)
  s_old(RC_U_N) = (rdisp(1) - drdisp(1)) * rc_law_per_deck
  call rc_update(rc_model, rc_par, rc_stiff, s_old, du, s_new, d, rc_tol, rc_tab, rc_h_ref, &
       rc_form, status)
  if (status /= RC_STICK .and. status /= RC_SLIP .and. status /= RC_OPEN) then
    pnewdt = 0.25_rc_dp  ! return mapping failed or closure beyond the tail: cut the increment
    return
  end if
  statev(1:RC_NSTATE) = s_new
  ! tractions to the local frame: STRESS(1) pressure (compression positive), shear t_loc = q t_lay
  stress(1) = s_new(RC_T_N)
  stress(2) = q(1, 1) * s_new(RC_T_X) + q(1, 2) * s_new(RC_T_Y)
  if (ndir > 2) stress(3) = q(2, 1) * s_new(RC_T_X) + q(2, 2) * s_new(RC_T_Y)
  ! tangent: rows/columns (N, t1, t2) from the law's (x, y, N), rotated, per deck length
  dlay = 0.0_rc_dp
  dlay(1, 1) = d(3, 3)
  dlay(1, 2:3) = d(3, 1:2)
  dlay(2:3, 1) = d(1:2, 3)
  dlay(2:3, 2:3) = matmul(q, matmul(d(1:2, 1:2), transpose(q)))
  dlay(2:3, 1) = matmul(q, dlay(2:3, 1))
  dlay(1, 2:3) = matmul(dlay(1, 2:3), transpose(q))
  do j = 1, ndir
    do i = 1, ndir
      ddsddr(i, j) = dlay(i, j) * rc_law_per_deck
    end do
  end do
  if (status == RC_OPEN) then
    lopenclose = 0
  else
    lopenclose = 1
  end if
  lstate = status
  ! frictional dissipation of the increment per area: law stress x law length -> deck length
  sfd = (s_new(RC_DISSIPATION) - s_old(RC_DISSIPATION)) / rc_law_per_deck
  ! mechanical only: no heat flux, no temperature dependence, no damping
  dviscous = 0.0_rc_dp
  dstructural = 0.0_rc_dp
  flux = 0.0_rc_dp
  ddfddt = 0.0_rc_dp
  ddsddt = 0.0_rc_dp
  ddfddr = 0.0_rc_dp
end subroutine uinter
