# bench/energy/power_sum.tcl: the power of every instance of the linked design (sta::instance_power, what
# report_power adds up), summed per group after `report_power`: seq (the flip-flops and latches, ff_*), comb (the
# rest of the standard cells), cut (the buffers bench/energy/activity.py puts where register and SRAM outputs were
# cut: their switching power is those nets'; their internal power the flow's own) and macro (the SRAM macros, which
# have no power model). Prints "group NAME INTERNAL SWITCHING LEAKAGE" (W) per group and "instances N nan K NAMES":
# an instance whose power OpenSTA 2.0.17 computes as Not a Number (0/0 in its activity propagation, which also stops
# report_power) is left out and named.
set corner [sta::cmd_corner]
foreach g {seq comb cut macro} { foreach c {0 1 2} { set power_sum($g,$c) 0.0 } }
set nan {}
set n 0
foreach inst [get_cells *] {
  set name [get_full_name $inst]
  set p [sta::instance_power $inst $corner]
  incr n
  if {[string match ff_* $name]} {
    set g seq
  } elseif {[string match r?buf_* $name]} {
    set g cut
  } elseif {[string match sram_* $name]} {
    set g macro
  } else {
    set g comb
  }
  set bad 0
  foreach c {0 1 2} {
    set v [lindex $p $c]
    if {![string is double -strict $v] || $v != $v} { set bad 1 }
  }
  if {$bad} { lappend nan $name; continue }
  foreach c {0 1 2} { set power_sum($g,$c) [expr {$power_sum($g,$c) + [lindex $p $c]}] }
}
foreach g {seq comb cut macro} { puts "group $g $power_sum($g,0) $power_sum($g,1) $power_sum($g,2)" }
puts "instances $n nan [llength $nan] $nan"
