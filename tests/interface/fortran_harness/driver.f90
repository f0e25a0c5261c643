! The gfortran harness of tests/interface/test_fortran_law.py: drives roughcontact_law.f90 and
! the Abaqus wrapper uinter.f90 (with a generated roughcontact_law_data.f90) from stdin and
! prints every result with 17 significant digits. First token of stdin, the mode:
!
!   points  n, then n rows: model par(7) stiff(3) form tabflag tol s_old(9) du(3)
!           -> per row: status s_new(9) D(3,3) (row by row)       [independent points]
!   path    model par(7) stiff(3) form tabflag tol s0(9), then n, then n rows du(3)
!           -> per step as points; the Fortran state is carried from step to step
!   uinter  alocaldir(3,3) (column by column) ndir statev0(9), then n, then n rows
!           rdisp(3) drdisp(3) -> per step: lopenclose lstate pnewdt sfd stress(3)
!           ddsddr(3,3) (row by row) statev(9); STATEV carried, as Abaqus does
!
! tabflag 1: the data module's table and h_ref; 0: no table (the constant-stiffness law).
program driver
  use roughcontact_law, only: rc_dp, rc_update, RC_NSTATE
  use roughcontact_law_data, only: rc_tab, rc_h_ref, rc_interaction
  implicit none
  character(len=16) :: mode
  integer :: n, k, model, form, tabflag, status
  real(rc_dp) :: par(7), stiff(3), tol, s_old(RC_NSTATE), du(3), s_new(RC_NSTATE), d(3, 3)

  read (*, *) mode
  select case (trim(mode))
  case ('points')
    read (*, *) n
    do k = 1, n
      read (*, *) model, par, stiff, form, tabflag, tol, s_old, du
      call step()
    end do
  case ('path')
    read (*, *) model, par, stiff, form, tabflag, tol, s_old
    read (*, *) n
    do k = 1, n
      read (*, *) du
      call step()
      s_old = s_new
    end do
  case ('uinter')
    call run_uinter()
  case default
    write (*, '(a)') 'unknown mode '//trim(mode)
    stop 2
  end select

contains

  subroutine step()
    real(rc_dp) :: empty(0, 4)
    if (tabflag == 1) then
      call rc_update(model, par, stiff, s_old, du, s_new, d, tol, rc_tab, rc_h_ref, form, status)
    else
      call rc_update(model, par, stiff, s_old, du, s_new, d, tol, empty, 0.0_rc_dp, form, status)
    end if
    write (*, '(i3, 18(1x, es25.17e3))') status, s_new, transpose(d)
  end subroutine step

  subroutine run_uinter()
    real(rc_dp) :: stress(3), ddsddr(3, 3), dvisc(3, 3), dstruct(3, 3), flux(2), ddfddt(2, 2)
    real(rc_dp) :: ddsddt(3, 2), ddfddr(2, 3), statev(RC_NSTATE), sed, sfd, spd, svd, scd, pnewdt
    real(rc_dp) :: rdisp(3), drdisp(3), temp(2), dtemp(2), predef(2, 1), dpred(2, 1), time(2)
    real(rc_dp) :: props(1), coords(3), alocaldir(3, 3), drot(2, 2)
    integer :: ndir, lopenclose, lstate, lsdi, kinc
    character(len=80) :: ciname, slname, msname
    read (*, *) alocaldir, ndir, statev
    read (*, *) n
    ciname = rc_interaction
    slname = 'SLAVE'
    msname = 'MASTER'
    stress = 0.0_rc_dp
    temp = 0.0_rc_dp
    dtemp = 0.0_rc_dp
    predef = 0.0_rc_dp
    dpred = 0.0_rc_dp
    props = 0.0_rc_dp
    coords = 0.0_rc_dp
    drot = reshape((/ 1.0_rc_dp, 0.0_rc_dp, 0.0_rc_dp, 1.0_rc_dp /), (/ 2, 2 /))
    lopenclose = -1
    lstate = -1
    sed = 0.0_rc_dp
    spd = 0.0_rc_dp
    svd = 0.0_rc_dp
    scd = 0.0_rc_dp
    do kinc = 1, n
      read (*, *) rdisp, drdisp
      time = (/ real(kinc, rc_dp), real(kinc, rc_dp) /)
      pnewdt = 1.0_rc_dp
      lsdi = 0
      sfd = 0.0_rc_dp
      ddsddr = 0.0_rc_dp
      call uinter(stress, ddsddr, dvisc, dstruct, flux, ddfddt, ddsddt, ddfddr, statev, sed, sfd, &
           spd, svd, scd, pnewdt, rdisp, drdisp, temp, dtemp, predef, dpred, time, 1.0_rc_dp, &
           0.0_rc_dp, ciname, slname, msname, props, coords, alocaldir, drot, 1.0_rc_dp, 1.0_rc_dp, &
           1, ndir, RC_NSTATE, 1, 0, 3, 1, kinc, 1, 0, lopenclose, lstate, lsdi, 0)
      write (*, '(2(i3, 1x), 23(1x, es25.17e3))') lopenclose, lstate, pnewdt, sfd, stress, &
           transpose(ddsddr), statev
    end do
  end subroutine run_uinter

end program driver

subroutine xit()
  ! Abaqus's XIT (terminate the analysis), for the harness
  write (*, '(a)') 'XIT called'
  stop 3
end subroutine xit
