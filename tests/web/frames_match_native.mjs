// The WASM decoder against the native one on streams whose compact chunk codes
// positions in surface frames (ext_spec A.6.1): binary64 arithmetic that every
// decoder must reproduce exactly, so every float32 position must be identical.
// usage: node frames_match_native.mjs WASM_DIR NAME.eqm:NAME.obj ...
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = path.resolve( path.dirname( fileURLToPath( import.meta.url ) ), '../..' );
const [ wasmDir, ...pairs ] = process.argv.slice( 2 );
const { default: createWasm } = await import( path.resolve( wasmDir, 'eqmesh_decoder.mjs' ) );
const { EqmeshDecoder } = await import( path.join( ROOT, 'web/EqmeshDecoder.js' ) );
const wasmBinary = fs.readFileSync( path.resolve( wasmDir, 'eqmesh_decoder.wasm' ) );
// No Draco module: these streams carry compact chunks only.
const decoder = await EqmeshDecoder.create( { createWasm, wasmBinary, warmUp: false, draco: {} } );
let failed = false;
for ( const pair of pairs ) {

	const [ stream, native ] = pair.split( ':' );
	const mesh = decoder.decode( new Uint8Array( fs.readFileSync( stream ) ) );
	const vertices = fs.readFileSync( native, 'utf8' ).split( '\n' ).filter( ( l ) => l.startsWith( 'v ' ) );
	let mismatches = vertices.length * 3 === mesh.positions.length ? 0 : 1;
	vertices.forEach( ( line, i ) => {

		line.trim().split( /\s+/ ).slice( 1, 4 ).forEach( ( v, k ) => {

			if ( Math.fround( Number( v ) ) !== mesh.positions[ 3 * i + k ] ) mismatches ++;

		} );

	} );
	console.log( `${path.basename( stream )}: ${vertices.length} vertices, ${mismatches} float32 mismatches` );
	failed = failed || mismatches > 0;

}
process.exit( failed ? 1 : 0 );
