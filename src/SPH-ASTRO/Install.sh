# Install/unInstall package files in LAMMPS (traditional make: make yes-sph-astro)
# mode = 0/1/2 for uninstall/install/update

mode=$1

# enforce using portable C locale
LC_ALL=C
export LC_ALL

# the gravity kspace styles derive from PPPM and MSM of the KSPACE package
if (test $mode = 1) then
  if (test ! -e ../pppm.cpp) then
    echo "Must install KSPACE package with SPH-ASTRO"
    exit 1
  fi
fi

# arg1 = file, arg2 = file it depends on

action () {
  if (test $mode = 0) then
    rm -f ../$1
  elif (! cmp -s $1 ../$1) then
    if (test -z "$2" || test -e ../$2) then
      cp $1 ..
      if (test $mode = 2) then
        echo "  updating src/$1"
      fi
    fi
  elif (test -n "$2") then
    if (test ! -e ../$2) then
      rm -f ../$1
    fi
  fi
}

for file in *.cpp *.h; do
  test -f ${file} && action $file
done

# HDF5 (C API, serial) for the snapshot output: Makefile.lammps of this folder defines
# sph_astro_SYSINC and sph_astro_SYSLIB (pkg-config hdf5; Debian: libhdf5-dev)

if (test $mode = 1) then

  if (test -e ../Makefile.package) then
    sed -i -e 's/[^ \t]*sph_astro[^ \t]* //g' ../Makefile.package
    sed -i -e 's|^PKG_SYSINC =[ \t]*|&$(sph_astro_SYSINC) |' ../Makefile.package
    sed -i -e 's|^PKG_SYSLIB =[ \t]*|&$(sph_astro_SYSLIB) |' ../Makefile.package
  fi

  if (test -e ../Makefile.package.settings) then
    sed -i -e '/^[ \t]*include.*SPH-ASTRO.*$/d' ../Makefile.package.settings
    # multiline form needed for BSD sed on Macs
    sed -i -e '4 i \
include ..\/SPH-ASTRO\/Makefile.lammps
' ../Makefile.package.settings
  fi

elif (test $mode = 0) then

  if (test -e ../Makefile.package) then
    sed -i -e 's/[^ \t]*sph_astro[^ \t]* //g' ../Makefile.package
  fi

  if (test -e ../Makefile.package.settings) then
    sed -i -e '/^[ \t]*include.*SPH-ASTRO.*$/d' ../Makefile.package.settings
  fi

fi
